// Threads of vdg's per-frame evaluation (normals, blends), internal to the vdg libraries.
//
// oneTBB runs the chunks; it stays behind one plain function (src/geom/parallel.cpp), so no public
// header includes TBB and a caller's own threads or TBB arenas are not constrained. A range shorter
// than two grains runs inline on the calling thread and never touches TBB, so small meshes pay
// nothing for threads. Longer ranges are split statically (about one chunk per worker thread, none
// shorter than `grain`); the first such call starts TBB's worker threads, which TBB keeps for the
// life of the process. Inside a caller's tbb::parallel_for (a crowd evaluated instance by instance)
// the chunks simply join the caller's arena.
#pragma once

#include <cstddef>
#include <type_traits>

namespace vdg::detail {

using ChunkFunction = void (*)(void* context, std::size_t begin, std::size_t end);
// Calls f(context, begin, end) over a partition of [0, count) into chunks of at least `grain`,
// from TBB's threads; returns when every chunk has run. No operator-new allocation of its own.
void runChunks(std::size_t count, std::size_t grain, ChunkFunction f, void* context);

// f(begin, end) over [0, count): inline when count < 2 * grain, else runChunks.
template <class F>
void parallelChunks(std::size_t count, std::size_t grain, F&& f) {
  if (count < 2 * grain) {
    if (count > 0) f(std::size_t{0}, count);
    return;
  }
  using Fn = std::remove_reference_t<F>;
  runChunks(
      count, grain, [](void* context, std::size_t begin, std::size_t end) { (*static_cast<Fn*>(context))(begin, end); },
      const_cast<void*>(static_cast<const void*>(&f)));
}

}  // namespace vdg::detail
