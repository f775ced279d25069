// Headers parsed once per build for every test program (cmake/BuildSpeed.cmake): the library set
// and GoogleTest.
#pragma once

#include "library.h"

#include <gtest/gtest.h>
