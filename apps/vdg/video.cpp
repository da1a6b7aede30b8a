#include "video.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"

namespace vdg::cli {
namespace {

namespace fs = std::filesystem;

// A fresh empty file beside `real` with the extension of `video` (ffmpeg picks the format from
// it), carrying the mode the target has, or would get as a new file.
std::string makeTemporaryBeside(const std::string& real, const std::string& where, const std::string& video) {
  const std::string ext = fs::path(video).extension().string();
  std::string name = (fs::path(real).parent_path() / (".vdg-XXXXXX" + ext)).string();
  const int fd = ::mkstemps(name.data(), static_cast<int>(ext.size()));
  if (fd < 0) throw Error(where + ": cannot write file: " + std::strerror(errno));
  const mode_t mask = ::umask(0);  // the tool is single-threaded here: read the umask and put it back
  ::umask(mask);
  struct stat existing {};
  (void)::fchmod(fd, ::stat(real.c_str(), &existing) == 0 ? existing.st_mode & 07777 : 0666 & ~mask);
  ::close(fd);
  return name;
}

}  // namespace

bool isVideoPath(std::string_view path) { return hasExtension(path, ".mp4") || hasExtension(path, ".gif"); }

void requireFfmpeg(const std::string& where, const std::string& instead) {
  if (!findOnPath("ffmpeg"))
    throw Error(where + ": writing a video needs the 'ffmpeg' program, which is not on PATH; install it, or " +
                instead);
}

void encodeVideo(const std::string& where, const std::string& video, const VideoFrames& frames) {
  const std::string real = checkedOutputPath(video);  // never through a link that leaves the folder
  struct stat existing {};
  if (::stat(real.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode))
    throw Error(where + ": is not a regular file; a video is written only to a file");
  const std::string temp = makeTemporaryBeside(real, where, video);
  const std::string filter = hasExtension(video, ".gif")
                                 ? "-vf 'split[a][b];[a]palettegen[p];[b][p]paletteuse'"
                                 : "-c:v libx264 -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2'";
  const std::string cmd = "ffmpeg -loglevel error -y -framerate 24 -start_number " + std::to_string(frames.first) +
                          " -i " + shellQuote((fs::path(frames.dir) / "frame_%04d.png").string()) + " -frames:v " +
                          std::to_string(frames.count) + " " + filter + " " + shellQuote(temp);
  std::error_code ec;
  if (std::system(cmd.c_str()) != 0) {
    fs::remove(temp, ec);
    keepNewOutputs();  // the frames stay for the user, as the message says
    throw Error(where + ": ffmpeg failed to encode the frames (they are in " + frames.dir + ")");
  }
  if (::rename(temp.c_str(), real.c_str()) != 0) {
    const int err = errno;
    fs::remove(temp, ec);
    throw Error(where + ": cannot write file: " + std::strerror(err));
  }
}

}  // namespace vdg::cli
