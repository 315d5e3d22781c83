// bin/pelage: answers `pelage --version` itself and hands every other command line to
// the command's body, lib/pelage/libpelage_cli.so (main.cpp), which it loads only then.
// Through OpenImageIO, OpenColorIO and Embree the body needs ~260 shared libraries, and
// loading and relocating them takes ~0.2 s before any of pelage's code runs; this
// program needs only the C and C++ runtimes. Plugins and data are still found relative
// to this executable: /proc/self/exe names it, not the library.
#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "apps/pelage/version.h"
#include "renderer/core/install_layout.h"

int main(int argc, char **argv) {
    if (argc == 2 && std::strcmp(argv[1], "--version") == 0) {
        std::puts(PELAGE_VERSION_LINE);
        return 0;
    }
    const std::string lib = pelage::renderer::package_lib_dir();
    if (lib.empty()) {
        std::fprintf(stderr, "pelage: cannot find this executable (/proc/self/exe)\n");
        return 1;
    }
    const std::string body = lib + "/libpelage_cli.so";
    // Lazy binding, as for the libraries an executable links; nothing else looks up the
    // body's symbols.
    void *handle = dlopen(body.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!handle) {
        const char *e = dlerror();
        std::fprintf(stderr, "pelage: cannot load the command's library: %s\n",
                     e ? e : body.c_str());
        return 1;
    }
    using Main = int (*)(int, char **);
    const auto body_main = reinterpret_cast<Main>(dlsym(handle, "pelage_cli_main"));
    if (!body_main) {
        std::fprintf(stderr,
                     "pelage: %s: no pelage_cli_main (a library of another build?)\n",
                     body.c_str());
        return 1;
    }
    return body_main(argc, argv);
}
