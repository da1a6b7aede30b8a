// Per-frame evaluation allocates nothing: counted through the global operator new.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "support/test_meshes.h"
#include "vdg/viewdep/model.h"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace vdg {
namespace {

TEST(ViewDependentModel, EvaluationAllocatesNothing) {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(10, 12);
  const Eigen::Vector3d views[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0.2, 0}};
  for (int k = 0; k < 4; ++k) {
    RawKey key;
    key.name = "k" + std::to_string(k);
    key.mesh = raw.base;
    key.mesh.positions[3 * static_cast<std::size_t>(k)] += 0.1f;
    key.view = views[k];
    raw.keys.push_back(key);
  }
  for (Uncovered mode : {Uncovered::Base, Uncovered::Cosine}) {
    raw.sphere.uncovered = mode;
    const ViewDependentModel model = ViewDependentModel::build(raw);
    std::vector<float> positions(raw.base.positions.size()), normals(positions.size());
    int hint = -1;
    const long before = g_allocations.load();
    for (int i = 0; i < 100; ++i) {
      const double t = i * 0.0628;
      model.evaluate(Eigen::Vector3d(std::sin(t), 0.3, std::cos(t)), 1.5, positions, normals, &hint);
    }
    EXPECT_EQ(g_allocations.load() - before, 0);
  }
}

}  // namespace
}  // namespace vdg
