// The headers that most test files include and that take most of their compile time (GoogleTest,
// Eigen, the standard library), precompiled once per build tree and given to every test program
// (vdg_add_test in cmake/VdgTargets.cmake; -DVDG_PCH=OFF turns it off, which is how to check that
// a test file includes what it uses). Only system headers: a change to vdg's own headers never
// rebuilds it.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <span>
#include <sstream>
#include <string>
#include <vector>
