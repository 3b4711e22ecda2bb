#pragma once
// Output files written so that nothing is lost (issue 12): the bytes go to a temporary file in the
// same folder, every write is checked, the file is flushed to disk and then renamed over the
// target, so an existing good file is replaced only by a complete new one. A target that exists
// and is not a regular file (/dev/null, /dev/full) is written directly, every write checked.
#include <string>

namespace snell {

/// Writes `bytes` to `path` as above; throws std::runtime_error naming the path and the reason
/// (the target is left as it was).
void write_file_atomically(const std::string& path, const std::string& bytes);

}  // namespace snell
