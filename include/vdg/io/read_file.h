// Reading a user's input file with limits: only regular files are read (a folder, a FIFO, a device
// such as /dev/zero or a socket is refused with a message naming it), and never more than a stated
// number of bytes, so hostile input can neither hang a reader nor exhaust memory.
#pragma once

#include <cstddef>
#include <string>

namespace vdg {

// Size limits of the formats vdg reads (bytes). A file larger than its limit is refused with a
// message naming the file, its size and the limit.
inline constexpr std::size_t kMaxJsonFileBytes = std::size_t{64} << 20;  // manifests, scripts, cameras
inline constexpr std::size_t kMaxMeshFileBytes = std::size_t{2} << 30;   // OBJ meshes

// The whole content of `path`. `what` names the kind of file in messages ("model", "edit script").
// Throws vdg::Error "PATH: ..." when the file is missing, is not a regular file, is unreadable or
// holds more than `max_bytes` bytes.
std::string readFileLimited(const std::string& path, const std::string& what, std::size_t max_bytes);

// Throws the same vdg::Error as readFileLimited would when `path` is not a readable regular file;
// for readers that hand the path to a library.
void checkInputFile(const std::string& path, const std::string& what);

}  // namespace vdg
