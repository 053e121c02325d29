// lrt/render/image.cpp: tangled from chapters/08-rendering.md. Edit the chapter, not this file.
#include "lrt/render/image.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

// Include the stb PNG writer and reader
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

namespace lrt {

// Image Method Definitions
Image::Image(int width, int height, const RGB &fill)
    : width(width), height(height) {
    if (width <= 0 || height <= 0 ||
        int64_t(width) * int64_t(height) > (int64_t(1) << 28))
        throw std::invalid_argument("Image: invalid size " +
                                    std::to_string(width) + "x" +
                                    std::to_string(height));
    pixels.assign(size_t(width) * size_t(height), fill);
}

size_t Image::Index(int x, int y) const {
    if (x < 0 || x >= width || y < 0 || y >= height)
        throw std::out_of_range("Image: pixel (" + std::to_string(x) + ", " +
                                std::to_string(y) + ") is outside the " +
                                std::to_string(width) + "x" +
                                std::to_string(height) + " image");
    return size_t(y) * size_t(width) + size_t(x);
}
std::vector<uint8_t> Image::EncodeSRGB8() const {
    std::vector<uint8_t> bytes(3 * pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i) {
        bytes[3 * i] = lrt::EncodeSRGB8(pixels[i].r);
        bytes[3 * i + 1] = lrt::EncodeSRGB8(pixels[i].g);
        bytes[3 * i + 2] = lrt::EncodeSRGB8(pixels[i].b);
    }
    return bytes;
}
void Image::WritePNG(const std::string &filename) const {
    if (pixels.empty())
        throw std::invalid_argument("Image::WritePNG: \"" + filename +
                                    "\": the image is empty");
    std::vector<uint8_t> bytes = EncodeSRGB8();
    errno = 0;
    std::FILE *f = std::fopen(filename.c_str(), "wb");
    if (!f)
        throw std::runtime_error("Image::WritePNG: cannot open \"" +
                                 filename + "\" for writing: " +
                                 std::strerror(errno));
    struct Sink {
        std::FILE *file;
        bool ok;
    } sink = {f, true};
    auto write = [](void *context, void *data, int size) {
        Sink *s = static_cast<Sink *>(context);
        size_t n = size_t(size);
        if (s->ok && std::fwrite(data, 1, n, s->file) != n) s->ok = false;
    };
    bool encoded = stbi_write_png_to_func(write, &sink, width, height, 3,
                                          bytes.data(), 3 * width) != 0;
    errno = 0;
    bool closed = std::fclose(f) == 0;
    if (!encoded || !sink.ok || !closed) {
        std::string reason = errno ? std::strerror(errno) : "write failed";
        std::remove(filename.c_str());
        throw std::runtime_error("Image::WritePNG: error writing \"" +
                                 filename + "\": " + reason);
    }
}
Image Image::ReadPNG(const std::string &filename) {
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<stbi_uc, void (*)(void *)> data(
        stbi_load(filename.c_str(), &w, &h, &channels, 3), stbi_image_free);
    if (!data)
        throw std::runtime_error("Image::ReadPNG: cannot read \"" + filename +
                                 "\": " + stbi_failure_reason());
    Image image(w, h);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = RGB(DecodeSRGB8(data.get()[3 * i]),
                              DecodeSRGB8(data.get()[3 * i + 1]),
                              DecodeSRGB8(data.get()[3 * i + 2]));
    return image;
}

}  // namespace lrt
