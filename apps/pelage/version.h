// The line `pelage --version` prints, the same from the launcher and from the body.
// PELAGE_VERSION ("0.1.0") and PELAGE_BUILD_INFO (the build type, and the sanitizers of
// a sanitizer build) come from apps/pelage/CMakeLists.txt.
#pragma once

#define PELAGE_VERSION_LINE "pelage " PELAGE_VERSION " (" PELAGE_BUILD_INFO ")"
