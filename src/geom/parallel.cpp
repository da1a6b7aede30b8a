// oneTBB behind vdg::detail::runChunks (see vdg/geom/parallel.h).
#include "vdg/geom/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace vdg::detail {

void runChunks(std::size_t count, std::size_t grain, ChunkFunction f, void* context) {
  // Static partitioning: the chunks are equal and known up front (streaming loops over arrays),
  // so work stealing would only add overhead.
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, count, grain == 0 ? 1 : grain),
      [&](const tbb::blocked_range<std::size_t>& r) { f(context, r.begin(), r.end()); }, tbb::static_partitioner());
}

}  // namespace vdg::detail
