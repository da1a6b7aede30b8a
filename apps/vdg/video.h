// Video output of the `vdg` tool, one way for every subcommand (render -o OUT.mp4, morph --video):
// the PNG frames DIR/frame_NNNN.png encoded by the external `ffmpeg` program into OUT.mp4 (H.264,
// even sides) or OUT.gif (a palette made from the frames), 24 frames per second.
#pragma once

#include <string>
#include <string_view>

namespace vdg::cli {

// True when `path` names a video this tool writes: it ends in .mp4 or .gif (any letter case).
bool isVideoPath(std::string_view path);

// Throws vdg::Error when ffmpeg is not on PATH, one line:
//   "<where>: writing a video needs the 'ffmpeg' program, which is not on PATH; install it, or <instead>"
// `where` names the option and the file ("-o out.mp4", "--video seq.gif"); `instead` says how to do
// without ("write PNG frames with -o DIR").
void requireFfmpeg(const std::string& where, const std::string& instead);

// The frames to encode: DIR/frame_NNNN.png for NNNN in [first, first + count).
struct VideoFrames {
  std::string dir;
  int first = 0;
  int count = 0;
};

// Encodes `frames` into `video` with ffmpeg, to a temporary file beside the real target (symbolic
// links followed, the target's mode kept), renamed over it only when ffmpeg succeeded; the frames
// are left in place. Throws vdg::Error starting with `where` ("-o out.mp4: ...") when the target is
// not a regular file, when ffmpeg fails (the message names the folder of the frames) or when the
// rename fails.
void encodeVideo(const std::string& where, const std::string& video, const VideoFrames& frames);

}  // namespace vdg::cli
