// libFuzzer target: the scene JSON loader (renderer/scene_file/scene_file.cpp), including
// the per-frame views a turntable render derives from it. Bad input must end in
// pelage::InputError; any other exception, crash or sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "renderer/scene_file/scene_file.h"
#include "renderer/scene_frame/scene_frame.h"
#include "sim/core/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const std::string text(reinterpret_cast<const char *>(data), size);
    try {
        const pelage::renderer::SceneDesc scene =
            pelage::renderer::parse_scene(text, "/fuzz/scene.json");
        // Frames are what render --frames asks for; the first and the last suffice.
        (void)pelage::renderer::scene_at_frame(scene, 0);
        (void)pelage::renderer::scene_at_frame(scene, scene.animation.frames - 1);
    } catch (const pelage::InputError &) {
    }
    return 0;
}
