// Writing outputs atomically (docs/design.md, "Conventions"): data goes to a temporary
// file in the destination's folder, which is renamed over the final name only once
// complete. A killed run never leaves a truncated file under the final name.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace pelage {

// Calls write(stream); on success renames the temporary into place. On any failure
// (the callback throws, or the stream goes bad) the temporary is removed, the
// destination is untouched, and std::runtime_error names the path.
void write_file_atomically(const std::string &path,
                           const std::function<void(std::ostream &)> &write);

}  // namespace pelage
