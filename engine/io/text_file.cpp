// write_text_file (bezinv/io.hpp): a whole text written as OUT is, through OutputTarget.
#include <string>
#include <string_view>

#include "bezinv/io.hpp"
#include "io/output_target.hpp"

namespace bezinv {

void write_text_file(const std::string& path, std::string_view contents) {
  detail::OutputTarget target(path, /*needs_seek=*/false);
  target.write(contents);
  target.commit();
}

}  // namespace bezinv
