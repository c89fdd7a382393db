#include "pipeline/workspace.hpp"

namespace bezinv::detail {

BatchWorkspace& batch_workspace() {
  thread_local BatchWorkspace workspace;
  return workspace;
}

}  // namespace bezinv::detail
