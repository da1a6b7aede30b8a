// Placeholder: the tests come with the implementation.
#include <gtest/gtest.h>
