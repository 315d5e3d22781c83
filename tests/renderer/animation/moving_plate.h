// Rigid plates moved by a node's clip, for motion blur: glTF files made in the tests.
#pragma once

#include <string>

namespace pelage::test {

// A plate [-1, 1] × [-2, 2] in the z = 0 plane facing +z, on a node whose clip "slide"
// (1 s) moves it linearly by +2 along x.
std::string sliding_plate();

// A bar [0, 3] × [-0.1, 0.1] in the z = 0 plane facing +z, on a node whose clip "spin"
// (1 s) turns it about +z from 0° to 90° at a constant rate (two keys, slerped).
std::string spinning_bar();

}  // namespace pelage::test
