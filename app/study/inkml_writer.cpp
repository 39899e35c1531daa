#include "app/study/inkml_writer.h"

#include <cstdio>
#include <cstring>
#include <string>

#include "app/study/csv_text.h"
#include "app/study/utf8_text.h"

namespace cb {
namespace {

std::string hex4(unsigned v) {
  char text[8];
  std::snprintf(text, sizeof text, "%04x", v);
  return text;
}

void writeProperty(std::ostream& out, const char* name, const std::string& value,
                   const char* units = nullptr) {
  out << "        <srcProperty name=\"" << name << "\" value=\"" << markupEscape(value) << '"';
  if (units) out << " units=\"" << units << '"';
  out << "/>\n";
}

void writeContext(std::ostream& out, const SessionTrace& trace, size_t n) {
  const PenDeviceInfo device = trace.device.value_or(PenDeviceInfo{});
  const std::string name(device.name, strnlen(device.name, sizeof device.name));
  out << "    <context xml:id=\"ctx-" << n << "\">\n";
  out << "      <inkSource xml:id=\"src-" << n << "\" model=\""
      << markupEscape(name.empty() ? "unknown device" : name) << "\" description=\""
      << markupEscape("cloudbrush session " + trace.id +
                      (trace.participant.empty() ? "" : ", participant " + trace.participant))
      << "\">\n";
  out << "        <traceFormat>\n";
  out << "          <channel name=\"X\" type=\"decimal\" units=\"mm\"/>\n";
  out << "          <channel name=\"Y\" type=\"decimal\" units=\"mm\"/>\n";
  out << "          <channel name=\"F\" type=\"integer\" min=\"0\" max=\"" << device.pressure_max
      << "\" units=\"dev\"/>\n";
  out << "          <channel name=\"OTx\" type=\"decimal\" units=\"deg\"/>\n";
  out << "          <channel name=\"OTy\" type=\"decimal\" units=\"deg\"/>\n";
  out << "          <channel name=\"T\" type=\"decimal\" units=\"ms\"/>\n";
  out << "        </traceFormat>\n";
  out << "        <sampleRate uniform=\"false\"/>\n";
  if (device.x_res > 0 && device.y_res > 0)
    out << "        <activeArea width=\"" << csvDouble(device.x_max / device.x_res)
        << "\" height=\"" << csvDouble(device.y_max / device.y_res) << "\" units=\"mm\"/>\n";
  writeProperty(out, "usbVendor", hex4(device.usb_vendor));
  writeProperty(out, "usbProduct", hex4(device.usb_product));
  writeProperty(out, "xMax", std::to_string(device.x_max), "dev");
  writeProperty(out, "yMax", std::to_string(device.y_max), "dev");
  writeProperty(out, "xResolution", csvDouble(device.x_res), "1/mm");
  writeProperty(out, "yResolution", csvDouble(device.y_res), "1/mm");
  writeProperty(out, "pressureMax", std::to_string(device.pressure_max), "dev");
  writeProperty(out, "tiltMin", std::to_string(device.tilt_min), "dev");
  writeProperty(out, "tiltMax", std::to_string(device.tilt_max), "dev");
  writeProperty(out, "tiltResolution", csvDouble(device.tilt_res), "1/deg");
  out << "      </inkSource>\n";
  out << "    </context>\n";
}

void writeTraces(std::ostream& out, const SessionTrace& trace, size_t n) {
  out << "  <traceGroup contextRef=\"#ctx-" << n << "\">\n";
  out << "    <annotation type=\"session\">" << markupEscape(trace.id) << "</annotation>\n";
  if (!trace.participant.empty())
    out << "    <annotation type=\"participant\">" << markupEscape(trace.participant)
        << "</annotation>\n";
  const std::vector<PenSample>& s = trace.samples;
  size_t i = 0;
  while (i < s.size()) {
    const bool down = s[i].tipDown();
    size_t end = i;
    while (end < s.size() && s[end].tipDown() == down) ++end;
    out << "    <trace type=\"" << (down ? "penDown" : "penUp") << "\">";
    for (size_t k = i; k < end; ++k) {
      if (k > i) out << ", ";
      out << csvDouble(s[k].x_mm) << ' ' << csvDouble(s[k].y_mm) << ' ' << s[k].pressure_raw << ' '
          << csvFloat(s[k].tilt_x_deg) << ' ' << csvFloat(s[k].tilt_y_deg) << ' '
          << decimalMillisecondsFromNs(elapsedNs(s[k].t_ns, trace.t0_ns));
    }
    out << "</trace>\n";
    i = end;
  }
  out << "  </traceGroup>\n";
}

}  // namespace

void beginInkml(std::ostream& out) {
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out << "<ink xmlns=\"http://www.w3.org/2003/InkML\">\n";
}

void writeInkmlSession(std::ostream& out, const SessionTrace& trace, size_t n) {
  out << "  <definitions>\n";
  writeContext(out, trace, n);
  out << "  </definitions>\n";
  writeTraces(out, trace, n);
}

void endInkml(std::ostream& out) {
  out << "</ink>\n";
}

void writeInkml(std::ostream& out, const std::vector<SessionTrace>& sessions) {
  beginInkml(out);
  for (size_t n = 0; n < sessions.size(); ++n) writeInkmlSession(out, sessions[n], n);
  endInkml(out);
}

}  // namespace cb
