#include "tests/hil/tablet/pen_corpus.h"

#include <fstream>
#include <sstream>

namespace cb::hil {

int32_t CorpusStep::value(const std::string& field) const {
  auto it = values.find(field);
  return it == values.end() ? 0 : it->second;
}

bool CorpusStep::expects(const std::string& word) const {
  std::istringstream parts(expect);
  for (std::string p; std::getline(parts, p, '+');)
    if (p == word) return true;
  return false;
}

bool CorpusDevice::i2c() const {
  return file.rfind("elan-usi", 0) == 0 || file.rfind("goodix", 0) == 0;
}

std::vector<CorpusDevice> readPenCorpus(const std::string& path, std::string* error) {
  std::vector<CorpusDevice> devices;
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open";
    return {};
  }
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    try {
      if (kind == "device") {
        CorpusDevice d;
        std::string vendor, product;
        words >> d.file >> vendor >> product >> d.report_id >> d.report_bytes;
        d.vendor = static_cast<uint16_t>(std::stoul(vendor, nullptr, 16));
        d.product = static_cast<uint16_t>(std::stoul(product, nullptr, 16));
        for (std::string w; words >> w;) {
          const size_t eq = w.find('='), dots = w.find("..", eq);
          if (eq == std::string::npos || dots == std::string::npos) throw std::invalid_argument(w);
          d.ranges[w.substr(0, eq)] = {std::stoi(w.substr(eq + 1, dots - eq - 1)),
                                       std::stoi(w.substr(dots + 2))};
        }
        devices.push_back(d);
      } else if (kind == "step") {
        if (devices.empty()) throw std::invalid_argument("step before any device");
        CorpusStep s;
        s.line = n;
        words >> s.name >> s.expect;
        for (std::string w; words >> w;) {
          if (w == "report") {
            std::string hex;
            words >> hex;
            for (size_t i = 0; i + 1 < hex.size(); i += 2)
              s.report.push_back(static_cast<uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
            break;
          }
          const size_t eq = w.find('=');
          if (eq == std::string::npos) throw std::invalid_argument(w);
          s.values[w.substr(0, eq)] = std::stoi(w.substr(eq + 1));
        }
        if (s.report.empty()) throw std::invalid_argument("step without a report");
        devices.back().steps.push_back(s);
      }
    } catch (const std::exception& e) {
      *error = path + ":" + std::to_string(n) + ": malformed line (" + e.what() + ")";
      return {};
    }
  }
  return devices;
}

std::string corpusMismatch(const CorpusStep& st, const PenSample& s, bool z_is_distance) {
  if (st.expect == "any") return {};
  if (st.expect == "out") return s.in_proximity ? "in proximity, expected out" : "";
  std::ostringstream why;
  auto check = [&](const char* what, long long got, long long want) {
    if (got != want) why << what << " " << got << " (expected " << want << ") ";
  };
  check("in_proximity", s.in_proximity, 1);
  check("rubber", s.tool == PenTool::kEraser, st.expects("rubber"));
  check("touch", s.tipDown(), st.expects("touch"));
  check("barrel", (s.buttons & kPenStylus1) != 0, st.expects("barrel"));
  check("barrel2", (s.buttons & kPenStylus2) != 0, st.expects("barrel2"));
  check("x", s.x_raw, st.value("x"));
  check("y", s.y_raw, st.value("y"));
  check("pressure", s.pressure_raw, st.value("tippressure"));
  check("tilt_x", s.tilt_x_raw, st.value("xtilt"));
  check("tilt_y", s.tilt_y_raw, st.value("ytilt"));
  if (z_is_distance) check("distance", s.distance_raw, st.value("z"));
  return why.str();
}

}  // namespace cb::hil
