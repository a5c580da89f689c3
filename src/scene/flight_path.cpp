#include "scene/flight_path.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/printable_text.hpp"

namespace penink {

namespace {

constexpr std::array<const char*, 7> column_names = {"position", "elevation", "azimuth", "altitude",
                                                     "light_azimuth", "light_altitude", "min_score"};
constexpr int required_columns = 4;

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

[[noreturn]] void fail(const std::string& file, int line, const std::string& what) {
    throw Error("batch", file, "line " + std::to_string(line) + ": " + what);
}

double parse_number(const std::string& text, const std::string& column, const std::string& file, int line) {
    double v = 0.0;
    const char* end = text.data() + text.size();
    const auto [p, ec] = std::from_chars(text.data(), end, v);
    if (text.empty() || ec != std::errc() || p != end || !std::isfinite(v))
        fail(file, line, column + ": not a number (\"" + printable_text(text) + "\")");
    return v;
}

// Column index of each known name (-1 when absent), from the header's fields.
std::array<int, column_names.size()> header_columns(const std::vector<std::string>& header,
                                                    const std::string& file, int line) {
    std::array<int, column_names.size()> at;
    at.fill(-1);
    for (std::size_t i = 0; i < header.size(); ++i) {
        const std::string name = lower(trim(header[i]));
        const auto it = std::find(column_names.begin(), column_names.end(), name);
        if (it == column_names.end()) fail(file, line, "unknown column \"" + printable_text(trim(header[i])) + "\"");
        const std::size_t k = std::size_t(it - column_names.begin());
        if (at[k] >= 0) fail(file, line, "column \"" + printable_text(name) + "\" given twice");
        at[k] = int(i);
    }
    for (int k = 0; k < required_columns; ++k)
        if (at[std::size_t(k)] < 0) fail(file, line, std::string("missing column \"") + column_names[std::size_t(k)] + "\"");
    return at;
}

FlightRecord parse_record(const std::vector<std::string>& f, const std::array<int, column_names.size()>& at,
                          const std::string& file, int line) {
    FlightRecord r;
    r.line = line;
    auto value = [&](std::size_t k) { return trim(f[std::size_t(at[k])]); };
    auto number = [&](std::size_t k) { return parse_number(value(k), column_names[k], file, line); };
    auto optional = [&](std::size_t k) -> std::optional<double> {
        if (at[k] < 0 || value(k).empty()) return std::nullopt;  // an empty cell keeps the scene's value
        return number(k);
    };
    r.position = value(0);
    if (r.position.empty()) fail(file, line, "position: empty");
    r.elevation = number(1), r.azimuth = number(2), r.altitude = number(3);
    if (r.altitude < -90.0 || r.altitude > 90.0) fail(file, line, "altitude: must be between -90 and 90 degrees");
    r.light_azimuth = optional(4), r.light_altitude = optional(5), r.min_score = optional(6);
    if (r.light_altitude && (*r.light_altitude < -90.0 || *r.light_altitude > 90.0))
        fail(file, line, "light_altitude: must be between 0 and 90 degrees (a sun above the horizon)");
    return r;
}

}  // namespace

bool split_csv_line(const std::string& line, std::vector<std::string>& fields) {
    fields.assign(1, "");
    bool quoted = false, closed = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c != '"') fields.back() += c;
            else if (i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
            else quoted = false, closed = true;
        } else if (c == ',') {
            fields.emplace_back(), closed = false;
        } else if (c == '"' && trim(fields.back()).empty() && !closed) {
            fields.back().clear(), quoted = true;
        } else if (closed && c != ' ' && c != '\t' && c != '\r') {
            return false;
        } else if (!closed) {
            fields.back() += c;
        }
    }
    return !quoted;
}

std::vector<FlightRecord> parse_flight_path(const std::string& text, const std::string& file) {
    std::istringstream in(text);
    std::string line;
    std::vector<std::string> fields;
    std::array<int, column_names.size()> at{};
    bool have_header = false;
    std::size_t header_size = 0;
    std::vector<FlightRecord> records;
    for (int n = 1; std::getline(in, line); ++n) {
        if (line.size() > max_flight_line_bytes)  // no record is this long; the parsers below are not for it
            fail(file, n, std::to_string(line.size()) + " bytes, more than the " + std::to_string(max_flight_line_bytes) +
                              " a line may have");
        const std::string t = trim(line);
        if (t.empty() || t[0] == '#') continue;
        if (!split_csv_line(line, fields)) fail(file, n, "unterminated or misplaced quote");
        if (!have_header) {
            at = header_columns(fields, file, n), header_size = fields.size(), have_header = true;
            continue;
        }
        if (fields.size() != header_size)
            fail(file, n, std::to_string(fields.size()) + " fields, header has " + std::to_string(header_size));
        records.push_back(parse_record(fields, at, file, n));
    }
    if (records.empty()) throw Error("batch", file, "no records (a header row and one line per frame expected)");
    return records;
}

std::vector<FlightRecord> read_flight_path(const std::string& path) {
    return parse_flight_path(read_input_text("batch", path, max_text_input_bytes, "flight path"), path);
}

}  // namespace penink
