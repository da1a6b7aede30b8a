// Video output of the `vdg` tool, one way for every subcommand (render -o OUT.mp4, morph --video):
// the PNG frames DIR/frame_NNNN.png encoded by the external `ffmpeg` program into OUT.mp4 (H.264,
// even sides) or OUT.gif (a palette made from the frames), 24 frames per second.
#pragma once

#include <string>
#include <string_view>

namespace vdg::cli {

// True when `path` names a video this tool writes: it ends in .mp4 or .gif (any letter case).
bool isVideoPath(std::string_view path);

// Throws vdg::Error when ffmpeg is not on PATH (or VDG_FFMPEG_TIMEOUT is not a valid number, see
// ffmpegTimeoutSeconds), one line:
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
// are left in place. ffmpeg runs as a child process of its own (stdin /dev/null, stdout discarded,
// stderr kept), in a process group of its own, and gets ffmpegTimeoutSeconds(frames.count): past
// that its process group is killed (SIGKILL) and reaped. Throws vdg::Error, one line starting with
// `where` ("-o out.mp4: ..."), when the target is not a regular file, when ffmpeg cannot be
// started, fails ("ffmpeg failed (exit status 1): <the last line ffmpeg wrote>; the frames are in
// DIR") or runs out of time, or when the rename fails; the temporary file is removed then.
void encodeVideo(const std::string& where, const std::string& video, const VideoFrames& frames);

// The seconds ffmpeg gets to encode `frame_count` frames: kFfmpegBaseSeconds plus
// kFfmpegSecondsPerFrame per frame (a 4096 x 4096 frame encodes in well under that on one core),
// unless the environment variable VDG_FFMPEG_TIMEOUT gives the seconds (a number > 0; for tests
// and for very slow machines). Throws vdg::Error for a VDG_FFMPEG_TIMEOUT that is not such a
// number.
inline constexpr double kFfmpegBaseSeconds = 60.0;
inline constexpr double kFfmpegSecondsPerFrame = 2.0;
double ffmpegTimeoutSeconds(long frame_count);

}  // namespace vdg::cli
