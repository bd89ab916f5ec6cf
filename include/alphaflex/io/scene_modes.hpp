#pragma once
// The scene's `modes:` section (docs/input.md, "Modal analysis"), read by `alphaflex modes`.
#include <mpi.h>

#include <string>
#include <vector>

#include "alphaflex/modal/modal_analysis.hpp"

namespace alphaflex {

/// The `modes:` keys of the scene `path` (defaults where absent), with the --set overrides of
/// modes.* and parameters.* applied. Collective over `comm`: rank 0 reads the file. Throws
/// InputError naming file, line and key.
ModalOptions read_modal_options(const std::string& path, const std::vector<std::string>& overrides, MPI_Comm comm);

}  // namespace alphaflex
