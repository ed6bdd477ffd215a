// stochtex — finding the OpenImageIO codec (image_codec.h): registered by a front-end that
// links OIIO, or loaded with dlopen from the module stochtex_oiio.so on first need.
//
// Where the module is looked for, first found wins:
//   1. $STOCHTEX_OIIO_MODULE (a file: tests, relocated installs);
//   2. beside the executable's folder: <exe>/../<libdir>/stochtex/ (installed: bin → lib) and
//      <exe>/../lib/stochtex/ (the build tree: every program of a build finds the one module);
//   3. the installed libdir, <prefix>/<libdir>/stochtex/ (programs outside the prefix).
#include "image/image_codec.h"

#include <stochtex/error.h>

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <vector>

namespace stochtex::codec {

namespace {

ImageCodec* registered = nullptr;

std::string executable_folder()
{
    std::error_code error;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
    return error ? std::string() : exe.parent_path().string();
}

struct Loaded {
    ImageCodec* codec = nullptr;
    std::string error;  // why it could not be loaded (the last place tried)
    std::string file;
};

Loaded load()
{
    Loaded result;
    std::vector<std::string> candidates;
    if (const char* path = std::getenv("STOCHTEX_OIIO_MODULE"); path && *path) {
        candidates.push_back(path);
    } else {
        const std::string name = "stochtex/stochtex_oiio.so";
        const std::string exe = executable_folder();
        if (!exe.empty()) {
            candidates.push_back(exe + "/" STOCHTEX_BIN_TO_LIBDIR "/" + name);
            candidates.push_back(exe + "/../lib/" + name);
        }
        candidates.push_back(STOCHTEX_INSTALL_LIBDIR "/" + name);
    }
    result.file = candidates.front();
    for (const std::string& file : candidates) {
        std::error_code ignored;
        if (candidates.size() > 1 && !std::filesystem::exists(file, ignored)) continue;
        result.file = file;
        // RTLD_LOCAL: OIIO's libraries stay out of the executable's symbol lookups.
        void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* reason = dlerror();
            result.error = reason ? reason : "dlopen failed";
            return result;
        }
        using Entry = ImageCodec* (*)(int);
        auto entry = reinterpret_cast<Entry>(dlsym(handle, "stochtex_image_codec"));
        if (!entry) {
            result.error = "no entry point stochtex_image_codec";
            return result;
        }
        result.codec = entry(module_interface_version);
        if (!result.codec) result.error = "built for another version of stochtex";
        return result;
    }
    result.error = "not found (set STOCHTEX_OIIO_MODULE to its path)";
    return result;
}

}  // namespace

void register_oiio_codec(ImageCodec* codec) { registered = codec; }

ImageCodec& oiio_codec(const std::string& why)
{
    if (registered) return *registered;
    static std::once_flag once;
    static Loaded loaded;
    std::call_once(once, [] { loaded = load(); });
    if (!loaded.codec)
        throw Error(why + " needs the OpenImageIO module " + loaded.file + ", which cannot be loaded: " + loaded.error);
    return *loaded.codec;
}

}  // namespace stochtex::codec
