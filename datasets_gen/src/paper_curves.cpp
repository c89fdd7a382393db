#include "bezinv/datasets/paper_curves.hpp"

namespace bezinv::datasets {

Curve paper_example1_curve() {
  return Curve::rational("paper-example-1", {4, 4, 3, 3, 7}, {1, 1, 1, 1, 3}, {2, 3, 3, 3, 4}, {1, 1, 1, 1, 1});
}

Curve paper_example2_curve() {
  return Curve::rational_bezier("paper-example-2",
                                {{14, 14}, {11, 15}, {9, 15}, {7, 15}, {4, 14}, {3, 12}, {3, 10}, {7, 8},
                                 {4, 6}, {14, 4}, {12, 2}, {8, 2}, {6, 2}, {4, 3}, {3, 4}, {2, 5}},
                                {2, 2, 2, 1, 2, 5, 5, 1, 3, 3, 3, 3, 2, 1, 1, 1});
}

Curve paper_example4_curve() {
  return Curve::rational_bezier("paper-example-4", {{1, 9}, {2, 1}, {5, 1}, {4, 1}}, {1, 2, 2, 1});
}

Curve default_cubic_curve() { return Curve::bezier("default-cubic", {{0, 0}, {1, 2}, {3, 2}, {4, 0}}); }

}  // namespace bezinv::datasets
