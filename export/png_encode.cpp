#include "export/png_encode.hpp"

#include <dlfcn.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

namespace penink {

namespace {

// The three zlib functions used, resolved from libz.so.1 (the handle stays open for the process).
struct Zlib {
    using Bound = unsigned long (*)(unsigned long);
    using Compress = int (*)(unsigned char*, unsigned long*, const unsigned char*, unsigned long, int);
    using Crc = unsigned long (*)(unsigned long, const unsigned char*, unsigned int);
    Bound bound = nullptr;
    Compress compress = nullptr;
    Crc crc = nullptr;
};

Zlib load_zlib() {
    void* lib = dlopen("libz.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib) throw std::runtime_error("zlib: cannot load libz.so.1");
    Zlib z;
    z.bound = reinterpret_cast<Zlib::Bound>(dlsym(lib, "compressBound"));
    z.compress = reinterpret_cast<Zlib::Compress>(dlsym(lib, "compress2"));
    z.crc = reinterpret_cast<Zlib::Crc>(dlsym(lib, "crc32"));
    if (!z.bound || !z.compress || !z.crc) throw std::runtime_error("zlib: libz.so.1 lacks compress2/crc32");
    return z;
}

void put32(std::string& out, std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out += char((v >> s) & 0xff);
}

void chunk(std::string& out, const Zlib& z, const char* type, const std::string& data) {
    put32(out, std::uint32_t(data.size()));
    const std::size_t start = out.size();
    out += type;
    out += data;
    const auto* p = reinterpret_cast<const unsigned char*>(out.data() + start);
    put32(out, std::uint32_t(z.crc(0, p, unsigned(out.size() - start))));
}

int paeth(int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return pa <= pb && pa <= pc ? a : (pb <= pc ? b : c);
}

// One row filtered with type f (0 None, 1 Sub, 2 Up, 3 Average, 4 Paeth); prev = row above or zeros.
void filter_row(const std::uint8_t* row, const std::uint8_t* prev, std::size_t n, int f, std::uint8_t* out) {
    for (std::size_t i = 0; i < n; ++i) {
        const int a = i >= 3 ? row[i - 3] : 0, b = prev[i], c = i >= 3 ? prev[i - 3] : 0;
        const int pred = f == 1 ? a : f == 2 ? b : f == 3 ? (a + b) / 2 : f == 4 ? paeth(a, b, c) : 0;
        out[i] = std::uint8_t(row[i] - pred);
    }
}

// Filtered scanlines, each with the filter of least sum of |signed bytes| (the usual heuristic).
std::string filtered(const RgbImage& img) {
    const std::size_t n = std::size_t(img.width) * 3;
    std::vector<std::uint8_t> zeros(n, 0), trial(n), best(n);
    std::string out;
    out.reserve((n + 1) * std::size_t(img.height));
    for (int y = 0; y < img.height; ++y) {
        const std::uint8_t* row = img.rgb.data() + std::size_t(y) * n;
        const std::uint8_t* prev = y > 0 ? row - n : zeros.data();
        long best_cost = -1;
        int best_f = 0;
        for (int f = 0; f < 5; ++f) {
            filter_row(row, prev, n, f, trial.data());
            long cost = 0;
            for (std::uint8_t v : trial) cost += std::abs(int(std::int8_t(v)));
            if (best_cost < 0 || cost < best_cost) best_cost = cost, best_f = f, best.swap(trial);
        }
        out += char(best_f);
        out.append(reinterpret_cast<const char*>(best.data()), n);
    }
    return out;
}

}  // namespace

std::string encode_png(const RgbImage& img, double dpi, const std::vector<std::pair<std::string, std::string>>& text) {
    static const Zlib z = load_zlib();  // immutable after first use: resolved function pointers
    std::string out = "\x89PNG\r\n\x1a\n";
    std::string ihdr;
    put32(ihdr, std::uint32_t(img.width)), put32(ihdr, std::uint32_t(img.height));
    ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bit, RGB, deflate, adaptive filter, no interlace
    chunk(out, z, "IHDR", ihdr);
    std::string phys;
    const auto ppm = std::uint32_t(std::lround(dpi / 0.0254));
    put32(phys, ppm), put32(phys, ppm), phys += char(1);  // pixels per metre
    chunk(out, z, "pHYs", phys);
    for (const auto& [k, v] : text) chunk(out, z, "tEXt", k + std::string(1, '\0') + v);
    const std::string raw = filtered(img);
    unsigned long size = z.bound(raw.size());
    std::string packed(size, '\0');
    if (z.compress(reinterpret_cast<unsigned char*>(packed.data()), &size,
                   reinterpret_cast<const unsigned char*>(raw.data()), raw.size(), 6) != 0)
        throw std::runtime_error("zlib: compress2 failed");
    packed.resize(size);
    chunk(out, z, "IDAT", packed);
    chunk(out, z, "IEND", "");
    return out;
}

}  // namespace penink
