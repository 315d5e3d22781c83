// create() and destroy() for a plugin written in C++, safe to call from C.
//
// The ABI is plain C: an exception leaving create() would unwind into the renderer's C
// call (std::terminate at best). guarded_create runs the plugin's own C++ function and
// turns whatever it throws into the ABI's refusal: NULL, with the message in `err`.
//
//     std::unique_ptr<Mine> make(const PelageParamSet &ps);  // may throw
//     const PelageShaderPlugin plugin = {..., sdk::guarded_create<make>, shade,
//                                        sdk::destroy_instance<Mine>};
#pragma once

#include <cstdio>
#include <exception>
#include <memory>
#include <stdexcept>

#include "shader/pelage_shader.h"

namespace pelage::shader::sdk {

// Fills `err` (when given) with `message`, cut to the ABI's 255 characters.
inline void set_error(PelageError *err, const char *message) noexcept {
    if (err) std::snprintf(err->message, sizeof(err->message), "%s", message);
}

// `Make`: a function (or other constant callable) taking the PelageParamSet and
// returning a std::unique_ptr to the instance; it may throw.
template <auto Make>
void *guarded_create(const PelageParamSet *ps, PelageError *err) noexcept {
    try {
        if (!ps) throw std::invalid_argument("create() received no parameter set");
        auto instance = Make(*ps);
        if (!instance) set_error(err, "create() made no instance");
        return instance.release();
    } catch (const std::exception &e) {
        set_error(err, e.what());
    } catch (...) {
        set_error(err, "create() failed with an exception that is not a std::exception");
    }
    return nullptr;
}

template <typename T>
void destroy_instance(void *self) noexcept {
    delete static_cast<T *>(self);
}

}  // namespace pelage::shader::sdk
