// Refines a DEM as `gdal_translate -q -r cubic -outsize F% F% -ot Float32 IN OUT` does (the same
// GDAL library call, GDALTranslate), for machines without gdal-bin: bench/scale_curve.sh builds
// and runs it when gdal_translate is missing.
// Usage: dem_refine IN OUT PERCENT
#include <cstdio>
#include <string>

#include <gdal.h>
#include <gdal_utils.h>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: dem_refine IN OUT PERCENT\n");
        return 2;
    }
    GDALAllRegister();
    GDALDatasetH in = GDALOpen(argv[1], GA_ReadOnly);
    if (!in) return 1;
    const std::string size = std::string(argv[3]) + "%";
    const char* args[] = {"-q", "-r", "cubic", "-outsize", size.c_str(), size.c_str(), "-ot", "Float32", nullptr};
    GDALTranslateOptions* options = GDALTranslateOptionsNew(const_cast<char**>(args), nullptr);
    int failed = 0;
    GDALDatasetH out = GDALTranslate(argv[2], in, options, &failed);
    GDALTranslateOptionsFree(options);
    if (out) GDALClose(out);
    GDALClose(in);
    return out && !failed ? 0 : 1;
}
