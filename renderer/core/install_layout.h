// Where pelage finds its parts: relative to the running executable (/proc/self/exe), so
// an installation works wherever its prefix is copied or moved. The build tree has the
// same layout as an installation (default GNUInstallDirs folders shown):
//   bin/pelage                   the command (apps/pelage/launcher.cpp)
//   lib/pelage/libpelage_cli.so  the command's body, loaded by bin/pelage
//   lib/pelage/shaders/*.so      the shader plugins (plugin_loader.h)
//   share/pelage/ocio/           the OpenColorIO config and its LUT
//   share/pelage/scenes/presets/ the Clonal Mosaic presets (in a build tree,
//                                share/pelage/scenes links to the source's scenes/)
// $PELAGE_DATA_DIR is searched before share/pelage for every data file or folder.
#pragma once

#include <string>

namespace pelage::renderer {

// The folder of the running executable; "" when /proc/self/exe cannot be read.
std::string executable_dir();

// The executable or shared library holding this code: lib/pelage/libpelage_cli.so
// under bin/pelage, which is only a launcher. A cache keyed by "this build" hashes it.
std::string code_file();

// lib/pelage and share/pelage of the installation (or build tree) the executable is in;
// "" when the executable's folder is unknown.
std::string package_lib_dir();
std::string package_data_dir();

// A file or folder of pelage's data, `relative` to a data folder ("scenes/presets",
// "ocio/config.ocio"): $PELAGE_DATA_DIR/relative when it exists, else
// package_data_dir()/relative when that exists, else the first of the two, so that the
// caller's error message names where it was expected.
std::string find_data(const std::string &relative);

}  // namespace pelage::renderer
