// A writer of universal-file datasets 58/58b for tests, written from the
// format statements (ID lines A80; record 6 2(I5,I10),2(1X,A10,I10,I4);
// record 7 3I10,3E13.5; records 8-11 I10,3I5,2(1X,A20); values 6E13.5 for
// single, 4E20.12 for double precision; 58b header I6,A1,I6,I6,I12,I12,...)
// the way pyuff and acquisition systems write them — independently of the
// reader in signal/uff58.cc.
#pragma once

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace beamid::testing {

enum class UffEncoding { kAsciiSingle, kAsciiDouble, kBinaryLittleFloat, kBinaryLittleDouble, kBinaryBigDouble };

struct UffChannel {
  std::string id_line1;             // usually the channel name
  std::string entity = "NONE";      // response entity name
  int node = 1;
  int direction = 3;                // +Z
  int function_type = 1;            // time response
  int ordinate_type = 0;            // 0: from the encoding (2 or 4)
  int spacing = 1;                  // even
  int ordinate_data_type = 0;       // 12 acceleration, 11 velocity, 13 force, 0 unknown
  std::string unit;                 // ordinate axis units label
  std::string abscissa_unit = "s";
  int abscissa_data_type = 17;      // time; 18 frequency
  int reference_node = 1, reference_direction = 3;
  int denominator_data_type = 0;    // record 10 (a frequency response's force: 13)
  std::string denominator_unit = "NONE";
  double x_min = 0.0;
  double dx = 0.0;
  int declared_values = -1;         // -1: values.size() (set the number of points for complex or uneven data)
  std::vector<double> values;
};

inline bool IsBinary(UffEncoding e) { return e != UffEncoding::kAsciiSingle && e != UffEncoding::kAsciiDouble; }
inline bool IsSingle(UffEncoding e) { return e == UffEncoding::kAsciiSingle || e == UffEncoding::kBinaryLittleFloat; }

// Rounds a value the way the encoding stores it.
inline double StoredValue(double value, UffEncoding encoding) {
  char text[40];
  switch (encoding) {
    case UffEncoding::kAsciiSingle: std::snprintf(text, sizeof text, "%13.5E", value); return std::stod(text);
    case UffEncoding::kAsciiDouble: std::snprintf(text, sizeof text, "%20.12E", value); return std::stod(text);
    case UffEncoding::kBinaryLittleFloat: return static_cast<float>(value);
    default: return value;
  }
}

// Some files start with other datasets; a 151 header must be skipped.
inline std::string Uff151Header() {
  return "    -1\n   151\nbeamid test model\nNONE\nbeamid test\n23-Nov-26 12:00:00\nbeamid\n"
         "23-Nov-26 12:00:00\nbeamid\n    -1\n";
}

inline std::string UffDataset58(const UffChannel& ch, UffEncoding encoding) {
  const bool single = IsSingle(encoding);
  const int n = ch.declared_values < 0 ? static_cast<int>(ch.values.size()) : ch.declared_values;
  const int ordinate_type = ch.ordinate_type ? ch.ordinate_type : (single ? 2 : 4);
  std::string header;
  char line[512];
  std::snprintf(line, sizeof line, "%-80s\n%-80s\n%-80s\n%-80s\n%-80s\n", ch.id_line1.c_str(), "NONE",
                "23-Nov-26 12:00:00", "beamid test record", "NONE");
  header += line;
  std::snprintf(line, sizeof line, "%5d%10d%5d%10d %-10s%10d%4d %-10s%10d%4d\n", ch.function_type, 0, 0, 0,
                ch.entity.c_str(), ch.node, ch.direction, "NONE", ch.reference_node, ch.reference_direction);
  header += line;
  std::snprintf(line, sizeof line, "%10d%10d%10d%13.5E%13.5E%13.5E\n", ordinate_type, n, ch.spacing, ch.x_min, ch.dx,
                0.0);
  header += line;
  std::snprintf(line, sizeof line, "%10d%5d%5d%5d %-20s %-20s\n", ch.abscissa_data_type, 0, 0, 0,
                ch.abscissa_data_type == 18 ? "Frequency" : "Time", ch.abscissa_unit.c_str());
  header += line;
  std::snprintf(line, sizeof line, "%10d%5d%5d%5d %-20s %-20s\n", ch.ordinate_data_type, 1, 0, 0, "Amplitude",
                ch.unit.c_str());
  header += line;
  std::snprintf(line, sizeof line, "%10d%5d%5d%5d %-20s %-20s\n", ch.denominator_data_type, 0, 0, 0, "NONE",
                ch.denominator_unit.c_str());
  header += line;
  std::snprintf(line, sizeof line, "%10d%5d%5d%5d %-20s %-20s\n", 0, 0, 0, 0, "NONE", "NONE");
  header += line;
  std::string out = "    -1\n";
  if (!IsBinary(encoding)) {
    out += "    58\n" + header;
    const int per_line = single ? 6 : 4;
    for (std::size_t i = 0; i < ch.values.size(); ++i) {
      std::snprintf(line, sizeof line, single ? "%13.5E" : "%20.12E", ch.values[i]);
      out += line;
      if ((i + 1) % per_line == 0 || i + 1 == ch.values.size()) out += '\n';
    }
  } else {
    const std::size_t width = single ? 4 : 8;
    const bool big = encoding == UffEncoding::kBinaryBigDouble;
    std::string bytes;
    for (double v : ch.values) {
      unsigned char raw[8];
      if (single) {
        const float f = static_cast<float>(v);
        std::memcpy(raw, &f, 4);
      } else {
        std::memcpy(raw, &v, 8);
      }
      if (big == (std::endian::native == std::endian::little))
        for (std::size_t a = 0, b = width - 1; a < b; ++a, --b) std::swap(raw[a], raw[b]);
      bytes.append(reinterpret_cast<const char*>(raw), width);
    }
    std::snprintf(line, sizeof line, "%6d%c%6d%6d%12d%12d%6d%6d%12d%12d\n", 58, 'b', big ? 2 : 1, 2, 11,
                  static_cast<int>(bytes.size()), 0, 0, 0, 0);
    out += line + header + bytes + "\n";
  }
  out += "    -1\n";
  return out;
}

}  // namespace beamid::testing
