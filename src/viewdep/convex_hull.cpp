#include "convex_hull.h"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "vdg/geom/error.h"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace vdg::detail {

std::vector<HullFacet> convexHull3d(const std::vector<double>& coords) {
  const int count = static_cast<int>(coords.size() / 3);
  // Qhull writes its diagnostics to a FILE*; collect them in memory for the error message.
  char* message_buffer = nullptr;
  std::size_t message_size = 0;
  FILE* messages = open_memstream(&message_buffer, &message_size);
  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, messages);
  std::vector<double> points(coords);  // qhull may modify its input
  char command[] = "qhull Qt";
  const int exit_code = qh_new_qhull(qh, 3, count, points.data(), False, command, nullptr, messages);
  std::vector<HullFacet> facets;
  if (exit_code == 0) {
    facetT* facet;
    FORALLfacets {
      if (facet->upperdelaunay && qh->DELAUNAY) continue;
      HullFacet out{};
      int k = 0;
      vertexT *vertex, **vertexp;
      FOREACHvertex_(facet->vertices) {
        if (k < 3) out.v[k] = qh_pointid(qh, vertex->point);
        ++k;
      }
      if (k != 3) continue;
      // Qhull stores vertices unordered; toporient says which way they turn.
      if (!facet->toporient) std::swap(out.v[1], out.v[2]);
      for (int c = 0; c < 3; ++c) out.normal[c] = facet->normal[c];
      out.offset = facet->offset;
      facets.push_back(out);
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  std::fclose(messages);
  std::string text = message_buffer ? std::string(message_buffer, message_size) : std::string();
  std::free(message_buffer);
  if (exit_code != 0) {
    const auto line_end = text.find('\n', text.find_first_not_of('\n'));
    throw Error("convex hull (Qhull) failed: " +
                (text.empty() ? std::string("error ") + std::to_string(exit_code) : text.substr(0, line_end)));
  }
  return facets;
}

}  // namespace vdg::detail
