// Counts heap allocations through the global operator new, for tests of the per-frame contract
// ("allocates nothing"). Link tests/support/allocation_counter.cpp into the test executable: it
// replaces the global operator new/delete for the whole program (once per executable).
#pragma once

namespace vdg::testing {

// Number of calls to the global operator new (any size, array forms included) so far.
long allocationCount();

// Allocations made while running `f`.
template <typename F>
long allocationsDuring(F&& f) {
  const long before = allocationCount();
  f();
  return allocationCount() - before;
}

}  // namespace vdg::testing
