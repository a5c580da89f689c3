#include "drainage/drainage_rasters.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include <gdal_priv.h>

#include "core/error.hpp"

namespace penink {

namespace {

struct DatasetCloser {
    void operator()(GDALDataset* d) const { GDALClose(d); }
};
using Dataset = std::unique_ptr<GDALDataset, DatasetCloser>;

// Source pixel coordinate of terrain node 0 and the step per terrain node along one axis.
void axis_map(bool flipped, int size, int offset, double& start, double& step) {
    start = flipped ? size - 0.5 - offset : offset + 0.5;
    step = flipped ? -1.0 : 1.0;
}

constexpr const char* owner_key = "PENINK_DRAINAGE_RASTER";

// GDAL's errors while a raster is written, kept rather than printed.
struct QuietErrors {
    QuietErrors() { CPLPushErrorHandler(CPLQuietErrorHandler), CPLErrorReset(); }
    ~QuietErrors() { CPLPopErrorHandler(); }
    bool failed() const { return CPLGetLastErrorType() >= CE_Failure; }
    std::string what() const {
        const std::string m = CPLGetLastErrorMsg();
        return m.empty() ? "GDAL failed" : m.substr(0, m.find('\n'));
    }
};

// Where one raster goes: the file written (`path`), the name errors show, its owner metadata item
// (`name`), its georeference and size (drainage points).
struct RasterFile {
    const std::string& path;
    const std::string& shown;
    const std::string& name;
    const DrainageGeoref& geo;
    int cols = 0, rows = 0;
};

template <class T, class A>
void write_raster(const RasterFile& file, GDALDataType type, const std::vector<T, A>& data, double nodata) {
    const std::string& path = file.path;
    const std::string& shown = file.shown;
    const DrainageGeoref& geo = file.geo;
    const int cols = file.cols, rows = file.rows;
    const QuietErrors errors;
    auto fail = [&] { throw Error("drainage", shown, "cannot write raster (" + errors.what() + ")"); };
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    char** opts = nullptr;
    opts = CSLSetNameValue(opts, "COMPRESS", "DEFLATE");
    opts = CSLSetNameValue(opts, "TILED", "YES");
    Dataset ds(drv ? drv->Create(path.c_str(), cols, rows, 1, type, opts) : nullptr);
    CSLDestroy(opts);
    if (!ds) fail();
    std::array<double, 6> gt = geo.gt;
    ds->SetGeoTransform(gt.data());
    if (!geo.wkt.empty()) ds->SetProjection(geo.wkt.c_str());
    ds->SetMetadataItem(owner_key, file.name.c_str());
    GDALRasterBand* band = ds->GetRasterBand(1);
    band->SetNoDataValue(nodata);
    if (band->RasterIO(GF_Write, 0, 0, cols, rows, const_cast<T*>(data.data()), cols, rows, type, 0, 0) != CE_None)
        fail();
    ds.reset();  // the compressed tiles are written here: a full disk shows now
    if (errors.failed()) fail();
}

}  // namespace

DrainageGeoref drainage_georef(const std::string& dem_path, const Terrain& t, int f) {
    GDALAllRegister();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    Dataset ds(static_cast<GDALDataset*>(GDALOpen(dem_path.c_str(), GA_ReadOnly)));
    CPLPopErrorHandler();
    if (!ds) throw Error("drainage", dem_path, "not a DEM raster (GDAL cannot read it)");
    std::array<double, 6> g{0.0, 1.0, 0.0, double(ds->GetRasterYSize()), 0.0, -1.0};
    ds->GetGeoTransform(g.data());
    DrainageGeoref geo;
    if (const OGRSpatialReference* srs = ds->GetSpatialRef()) {
        char* wkt = nullptr;
        srs->exportToWkt(&wkt);
        geo.wkt = wkt ? wkt : "";
        CPLFree(wkt);
    }
    double a, sa, b, sb;  // read_dem puts west at column 0 and north at row 0
    axis_map(g[1] < 0.0, ds->GetRasterXSize(), t.source_col0, a, sa);
    axis_map(g[5] > 0.0, ds->GetRasterYSize(), t.source_row0, b, sb);
    // fine pixel coordinate i' (centre i + 0.5) -> source pixel a + sa * (i' - 0.5) / f
    const double a0 = a - 0.5 * sa / f, b0 = b - 0.5 * sb / f;
    geo.gt = {g[0] + g[1] * a0 + g[2] * b0, g[1] * sa / f, g[2] * sb / f,
              g[3] + g[4] * a0 + g[5] * b0, g[4] * sa / f, g[5] * sb / f};
    return geo;
}

std::vector<std::string> drainage_raster_names() {
    return {"flow_direction.tif", "accumulation.tif", "basin.tif", "stream_order.tif"};
}

bool is_drainage_raster(const std::string& path) {
    GDALAllRegister();
    const QuietErrors quiet;
    const char* const gtiff[] = {"GTiff", nullptr};
    Dataset ds(GDALDataset::FromHandle(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, gtiff, nullptr, nullptr)));
    return ds && ds->GetMetadataItem(owner_key) != nullptr;
}

void write_drainage_raster(std::size_t which, const std::string& path, const std::string& shown,
                           const DrainageGeoref& geo, int cols, int rows, const std::vector<std::uint8_t>& valid,
                           const DrainageResult& res) {
    GDALAllRegister();
    const std::string name = drainage_raster_names().at(which);
    const RasterFile file{path, shown, name, geo, cols, rows};
    if (which == 0) {
        std::vector<std::uint8_t> codes = res.dir;
        for (std::size_t i = 0; i < codes.size(); ++i)
            if (!valid[i]) codes[i] = 255;
        write_raster(file, GDT_Byte, codes, 255.0);
    } else if (which == 1) {
        write_raster(file, GDT_UInt32, res.net.acc, 0.0);
    } else if (which == 2) {
        write_raster(file, GDT_UInt32, res.net.basin, 0.0);
    } else {
        write_raster(file, GDT_Byte, res.net.order, 0.0);
    }
}

struct HeightRasterWriter::State {
    std::string shown, stage;
    Error failed(const std::string& why) const { return Error(stage, shown, "cannot write raster (" + why + ")"); }
    int cols = 0, rows = 0;
    Dataset ds;
    std::vector<float> row;  // a strip's values with NaN at nodata
};

HeightRasterWriter::HeightRasterWriter(const std::string& path, const std::string& shown, const DrainageGeoref& geo,
                                       int cols, int rows, const std::string& stage)
    : s_(std::make_unique<State>()) {
    GDALAllRegister();
    s_->shown = shown, s_->stage = stage, s_->cols = cols, s_->rows = rows;
    const QuietErrors errors;
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    char** opts = nullptr;
    opts = CSLSetNameValue(opts, "COMPRESS", "DEFLATE");
    opts = CSLSetNameValue(opts, "PREDICTOR", "3");
    opts = CSLSetNameValue(opts, "ZLEVEL", "1");  // the header says why
    opts = CSLSetNameValue(opts, "BLOCKYSIZE", std::to_string(height_raster_strip_rows).c_str());
    opts = CSLSetNameValue(opts, "BIGTIFF", "IF_SAFER");
    opts = CSLSetNameValue(opts, "NUM_THREADS", "ALL_CPUS");
    s_->ds.reset(drv ? drv->Create(path.c_str(), cols, rows, 1, GDT_Float32, opts) : nullptr);
    CSLDestroy(opts);
    if (!s_->ds) throw s_->failed(errors.what());
    std::array<double, 6> gt = geo.gt;
    s_->ds->SetGeoTransform(gt.data());
    if (!geo.wkt.empty()) s_->ds->SetProjection(geo.wkt.c_str());
    s_->ds->GetRasterBand(1)->SetNoDataValue(std::numeric_limits<double>::quiet_NaN());
    if (errors.failed()) throw s_->failed(errors.what());
}

HeightRasterWriter::~HeightRasterWriter() = default;

void HeightRasterWriter::write_rows(int y0, int y1, const float* z, const std::uint8_t* valid) {
    if (!s_->ds || y0 < 0 || y1 > s_->rows || y0 >= y1) return;
    const QuietErrors errors;
    const std::size_t n = std::size_t(y1 - y0) * std::size_t(s_->cols);
    s_->row.resize(n);
    for (std::size_t i = 0; i < n; ++i) s_->row[i] = valid[i] ? z[i] : std::numeric_limits<float>::quiet_NaN();
    if (s_->ds->GetRasterBand(1)->RasterIO(GF_Write, 0, y0, s_->cols, y1 - y0, s_->row.data(), s_->cols, y1 - y0,
                                           GDT_Float32, 0, 0) != CE_None ||
        errors.failed())
        throw s_->failed(errors.what());
}

void HeightRasterWriter::close() {
    const QuietErrors errors;
    if (s_->ds) s_->ds->FlushCache();
    s_->ds.reset();  // the last strips are written here: a full disk shows now
    if (errors.failed()) throw s_->failed(errors.what());
}

}  // namespace penink
