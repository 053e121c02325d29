// lrt/render/image.h: tangled from chapters/08-rendering.md. Edit the chapter, not this file.
#pragma once

#include "lrt/core/base.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace lrt {

// RGB Declarations
struct RGB {
    RGB() {}
    RGB(Float r, Float g, Float b) : r(r), g(g), b(b) {}
    RGB operator+(const RGB &c) const { return RGB(r + c.r, g + c.g, b + c.b); }
    RGB operator*(const RGB &c) const { return RGB(r * c.r, g * c.g, b * c.b); }
    RGB operator*(Float s) const { return RGB(r * s, g * s, b * s); }
    bool operator==(const RGB &c) const {
        return r == c.r && g == c.g && b == c.b;
    }
    bool operator!=(const RGB &c) const { return !(*this == c); }
    Float r = 0, g = 0, b = 0;
};

// Image Declarations
class Image {
  public:
    Image() {}
    Image(int width, int height, const RGB &fill = RGB());
    int Width() const { return width; }
    int Height() const { return height; }
    RGB &operator()(int x, int y) { return pixels[Index(x, y)]; }
    const RGB &operator()(int x, int y) const { return pixels[Index(x, y)]; }
    // Image Public Methods
    std::vector<uint8_t> EncodeSRGB8() const;
    void WritePNG(const std::string &filename) const;
    static Image ReadPNG(const std::string &filename);

  private:
    size_t Index(int x, int y) const;
    int width = 0, height = 0;
    std::vector<RGB> pixels;
};

// Image Inline Functions
inline Float GammaCorrect(Float v) {
    // Apply the sRGB transfer function to v
    if (v <= Float(0.0031308)) return Float(12.92) * v;
    return Float(1.055) * std::pow(v, Float(1 / 2.4)) - Float(0.055);
}

inline Float InverseGammaCorrect(Float v) {
    if (v <= Float(0.04045)) return v / Float(12.92);
    return std::pow((v + Float(0.055)) / Float(1.055), Float(2.4));
}
inline uint8_t EncodeSRGB8(Float v) {
    if (!(v > 0)) return 0;
    if (v >= 1) return 255;
    // Encode v and round it to the nearest byte
    return uint8_t(Float(255) * GammaCorrect(v) + Float(0.5));
}

inline Float DecodeSRGB8(uint8_t b) {
    return InverseGammaCorrect(Float(b) / Float(255));
}

}  // namespace lrt
