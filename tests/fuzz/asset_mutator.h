#pragma once
// Structure-aware mutation of the binary and text assets a scene reads, for the loader's fuzz
// target (issue 30: the fuzzer mutated the XML by structure but assets only as bytes, which
// rarely hits a header's counts, sizes or offsets, and every defect of that round sat there).
// Each mutation keeps the file recognisable as its format, so that it reaches the reader's
// checks: a header's width, height, vertex or face count, an offset-table entry or a field inside
// a compressed stream set to an edge value (checksums and compression redone), or the file cut
// short.
#include <cstdint>
#include <string>

namespace snell::fuzz {

/// Mutates `data`, a file named `name`, by its extension: .serialized (offset table, the counts
/// inside its zlib stream), .ply and .obj (element counts, indices), .hdr (resolution line, RLE
/// scanline headers), .png (IHDR with its CRC), .exr (data and display windows, line offsets),
/// .jpg (frame size), .vol (grid header); any file may be truncated. Returns false, leaving
/// `data` as it was, when it has nothing to mutate; the caller then mutates its bytes.
bool mutate_asset(const std::string& name, std::string& data, uint64_t seed);

}  // namespace snell::fuzz
