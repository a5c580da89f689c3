// A flight path for `penink batch` (Mower, "Concurrent Drainage Network Rendering", section 3: animation): a CSV file with a header
// row naming its columns, one camera (and optional light / crease threshold) per record.
// Columns (any order, names case-insensitive): position (UTM "E N 18N", "lon,lat" quoted, or
// "x y" in the DEM's CRS: conventions.md), elevation (metres above the DEM's datum), azimuth,
// altitude (degrees, view direction); optional light_azimuth, light_altitude (degrees) and
// min_score (crease threshold of eq. 6). Fields may be double-quoted ("" is a quote); blank lines
// and lines starting with # are skipped. Line numbers count every physical line from 1.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace penink {

struct FlightRecord {
    int line = 0;                  // line of the CSV file it came from
    std::string position;          // as written; parsed against the DEM by the caller
    double elevation = 0.0, azimuth = 0.0, altitude = 0.0;
    std::optional<double> light_azimuth, light_altitude, min_score;
};

// Splits one CSV line into fields (RFC 4180 quoting within one line). Returns false on an
// unterminated quote or text after a closing quote.
bool split_csv_line(const std::string& line, std::vector<std::string>& fields);

// Parses CSV text; `file` names it in errors: penink::Error(stage "batch", file,
// "line N: WHAT"), e.g. "line 3: azimuth: not a number (\"abc\")", "line 1: missing column
// \"elevation\"", "line 4: 3 fields, header has 4", "no records", "line 2: N bytes, more than
// the 4096 a line may have" (max_flight_line_bytes).
inline constexpr std::size_t max_flight_line_bytes = 4096;
std::vector<FlightRecord> parse_flight_path(const std::string& text, const std::string& file);

// Reads and parses a file: "cannot read file" when it cannot be opened.
std::vector<FlightRecord> read_flight_path(const std::string& path);

}  // namespace penink
