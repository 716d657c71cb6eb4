#pragma once
// findImageDamage: whether a PNG or JPEG file is whole, read through once
// without decoding it.
//
// readImageHeader (image_header.h) looks at a frame's first bytes only, so
// a frame cut short by a full disk or a failed copy, or with bytes
// overwritten in its image data, passes it and is found only when the
// front-end decodes it, deep into a run. Decoding every frame to check it
// costs tens of seconds per thousand frames; reading each file once costs
// what the disk reads:
//   PNG   the chunks are walked from the signature: each chunk's length
//         must fit in the file, its CRC-32 (zlib's crc32, over type and
//         data, PNG specification section 5.3) must match, and the walk must
//         end at the IEND chunk. A truncated file has no IEND; a changed
//         byte fails its chunk's CRC.
//   JPEG  the file must end with the end-of-image marker FF D9 (trailing
//         zero bytes, which some writers pad with, are allowed). JPEG has no
//         checksum: a changed byte in the entropy-coded data is found only by
//         decoding.
// nullopt: whole; otherwise the reason in words, e.g. "truncated: the file
// ends at byte 30211, inside the IDAT chunk that starts at byte 20033".

#include <filesystem>
#include <optional>
#include <string>

namespace hsmap {

// Throws InputError when the file cannot be opened (not a regular file);
// a file that is neither PNG nor JPEG is reported as damage.
std::optional<std::string> findImageDamage(const std::filesystem::path& file);

}  // namespace hsmap
