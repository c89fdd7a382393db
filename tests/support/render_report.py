"""The stress report in a real browser: loads DIR/index.html in headless chromium, then prints
   <svg plots in the rendered DOM> <fewest marks in one plot> <non-white pixel fraction> <colours>
of the page as the browser laid it out and painted it (the screenshot decoded here, with zlib:
Debian's Python has no image library).

usage: render_report.py BROWSER INDEX_HTML WORK_DIR"""
import html.parser
import os
import struct
import subprocess
import sys
import zlib


def browser_run(browser, args, work):
    # --no-sandbox: the tests may run as root, where chromium refuses its sandbox.
    common = ['--headless', '--no-sandbox', '--disable-gpu', '--hide-scrollbars', '--mute-audio',
              '--user-data-dir=' + os.path.join(work, 'profile')]
    return subprocess.run([browser] + common + args, capture_output=True, text=True, timeout=120)


class Marks(html.parser.HTMLParser):
    """Counts each <svg>'s elements of class "mark" (the report's data marks)."""

    def __init__(self):
        super().__init__()
        self.plots = []

    def handle_starttag(self, tag, attrs):
        if tag == 'svg':
            self.plots.append(0)
        if self.plots and 'mark' in (dict(attrs).get('class') or '').split():
            self.plots[-1] += 1


def png_pixels(data):
    """(width, height, rows of RGB(A) bytes) of an 8-bit, non-interlaced RGB or RGBA PNG."""
    assert data[:8] == b'\x89PNG\r\n\x1a\n', 'not a PNG'
    pos, idat, header = 8, b'', None
    while pos < len(data):
        length, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b'IHDR':
            header = struct.unpack('>IIBBBBB', body)
        elif kind == b'IDAT':
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and colour in (2, 6) and interlace == 0, header
    bpp = 3 if colour == 2 else 4
    raw, stride, rows, prior = zlib.decompress(idat), width * bpp, [], bytearray(width * bpp)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prior[i]
            c = prior[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prior = line
    return width, height, bpp, rows


def main():
    browser, page, work = sys.argv[1:4]
    url = 'file://' + os.path.abspath(page)
    dom = browser_run(browser, ['--dump-dom', url], work)
    if dom.returncode != 0:
        sys.exit('dump-dom failed: ' + dom.stderr[-2000:])
    marks = Marks()
    marks.feed(dom.stdout)
    shot = os.path.join(work, 'page.png')
    run = browser_run(browser, ['--window-size=1280,2400', '--screenshot=' + shot, url], work)
    if run.returncode != 0 or not os.path.exists(shot):
        sys.exit('screenshot failed: ' + run.stderr[-2000:])
    width, height, bpp, rows = png_pixels(open(shot, 'rb').read())
    inked, colours = 0, set()
    for line in rows:
        for x in range(0, width * bpp, bpp * 2):  # every other pixel: enough to tell blank from not
            r, g, b = line[x], line[x + 1], line[x + 2]
            colours.add((r >> 4, g >> 4, b >> 4))
            inked += min(r, g, b) < 200
    print(len(marks.plots), min(marks.plots) if marks.plots else 0, inked / (width * height / 2), len(colours))


if __name__ == '__main__':
    main()
