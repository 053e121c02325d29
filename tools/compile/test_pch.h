// The headers every test translation unit reads, precompiled once per build
// variant by tools/make/asof.mk and given to each test compile with -include:
// GoogleTest alone is most of a test's compile time. Only headers from outside
// the book belong here, so the precompiled header holds for every chapter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>
