#include "tune/report_html.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "tune/paired_timing.h"

namespace spire::tune {
namespace {

// The SVG's size and the plot's box within it; the panel right of the plot
// shows the hovered point.
constexpr double kWidth = 980;
constexpr double kHeight = 560;
constexpr double kLeft = 80;
constexpr double kRight = 680;
constexpr double kTop = 20;
constexpr double kBottom = 500;
constexpr double kPanelLeft = 700;
constexpr double kPanelWidth = 270;
constexpr int kTicks = 5;

constexpr const char* kStyle = R"(
body { font: 14px/1.4 sans-serif; margin: 24px; color: #222; }
table { border-collapse: collapse; margin: 12px 0; }
th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: left; vertical-align: top; }
svg text { font: 12px sans-serif; fill: #333; }
svg .label { font-size: 14px; }
.axis { stroke: #333; }
.grid { stroke: #e6e6e6; }
.pt circle { fill: #7f93b0; }
.pt.front circle { fill: #d2281e; }
.pt.noise circle { fill: #fff; stroke: #e08a00; stroke-width: 2.5; }
.pt:hover circle { stroke: #000; stroke-width: 2; }
.bar { stroke: #d2281e; stroke-width: 1.5; }
.noise .bar { stroke: #e08a00; }
.frontline { fill: none; stroke: #d2281e; stroke-width: 1.5; }
.tip { display: none; pointer-events: none; }
.pt:hover .tip { display: inline; }
.panel { fill: #fafafa; stroke: #bbb; }
.key { display: inline-block; width: 10px; height: 10px; border-radius: 50%; margin: 0 4px 0 12px; }
.key.other { background: #7f93b0; }
.key.front { background: #d2281e; }
.key.noise { background: #fff; border: 2px solid #e08a00; width: 7px; height: 7px; }
)";

// Frame time and RMSE to the plot's coordinates; both axes start at 0.
struct Scale {
  double xMax = 1.0;
  double yMax = 1.0;
  double xStep = 0.2;
  double yStep = 0.2;
  double x(double ms) const { return kLeft + ms / xMax * (kRight - kLeft); }
  double y(double error) const { return kBottom - error / yMax * (kBottom - kTop); }
};

// What the page knows of each result beyond the result itself.
struct PointRoles {
  std::set<size_t> front;
  std::set<size_t> noise;  // front points whose interval overlaps a neighbour's on the front
};

bool plotted(const VariantResult& r) {
  return r.ok() && r.nanPixels + r.infPixels == 0 && std::isfinite(r.rmse) && std::isfinite(r.frameMs);
}

// A step of 1, 2 or 5 times a power of ten that divides [0, max] into about
// kTicks parts.
double niceStep(double max) {
  const double raw = max / kTicks;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * magnitude >= raw) return m * magnitude;
  }
  return 10.0 * magnitude;
}

// The time interval of result `r` in milliseconds, when it has one.
bool intervalMs(const ReportPage& page, const VariantResult& r, double& low, double& high) {
  if (r.time.pairs == 0 || page.referenceMs <= 0.0) return false;
  low = r.time.interval.low * page.referenceMs;
  high = r.time.interval.high * page.referenceMs;
  return std::isfinite(low) && std::isfinite(high);
}

Scale scaleFor(const ReportPage& page, const PointRoles& roles) {
  double maxMs = 0.0;
  double maxError = 0.0;
  for (size_t i = 0; i < page.results.size(); ++i) {
    const VariantResult& r = page.results[i];
    if (!plotted(r)) continue;
    maxMs = std::max(maxMs, r.frameMs);
    maxError = std::max(maxError, r.rmse);
    double low = 0.0;
    double high = 0.0;
    if (roles.front.count(i) && intervalMs(page, r, low, high)) maxMs = std::max(maxMs, high);
  }
  Scale scale;
  if (maxMs > 0.0) scale.xStep = niceStep(maxMs * 1.05);
  if (maxError > 0.0) scale.yStep = niceStep(maxError * 1.05);
  scale.xMax = maxMs > 0.0 ? std::ceil(maxMs * 1.05 / scale.xStep) * scale.xStep : 1.0;
  scale.yMax = maxError > 0.0 ? std::ceil(maxError * 1.05 / scale.yStep) * scale.yStep : 1.0;
  return scale;
}

PointRoles rolesOf(const ReportPage& page) {
  PointRoles roles;
  roles.front.insert(page.front.begin(), page.front.end());
  for (size_t k = 1; k < page.front.size(); ++k) {
    const size_t previous = page.front[k - 1];
    const size_t current = page.front[k];
    if (withinNoise(page.results[previous].time, page.results[current].time)) {
      roles.noise.insert(previous);
      roles.noise.insert(current);
    }
  }
  return roles;
}

std::string decisionsText(const ReportPage& page, const VariantResult& r, std::string_view separator) {
  std::string text;
  for (size_t c = 0; c < page.components.size() && c < r.placements.size(); ++c) {
    text += fmt::format("{}{}={}", text.empty() ? "" : separator, page.components[c], r.placements[c]);
  }
  return text;
}

std::string timeText(const ReportPage& page, const VariantResult& r) {
  double low = 0.0;
  double high = 0.0;
  if (!intervalMs(page, r, low, high)) return fmt::format("{:.3f} ms", r.frameMs);
  return fmt::format("{:.3f} ms (95% interval {:.3f}-{:.3f}, {} pairs)", r.frameMs, low, high, r.time.pairs);
}

// A line of the plot, in the SVG's coordinates.
struct Segment {
  double x1 = 0.0;
  double y1 = 0.0;
  double x2 = 0.0;
  double y2 = 0.0;
};

std::string svgLine(const char* kind, const Segment& s) {
  return fmt::format("<line class=\"{}\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\"/>", kind, s.x1, s.y1,
                     s.x2, s.y2);
}

// The values of an axis's ticks: multiples of `step` from 0 to `max`.
std::vector<double> tickValues(double step, double max) {
  std::vector<double> values;
  for (int k = 0; k * step <= max * (1 + 1e-9); ++k) values.push_back(k * step);
  return values;
}

// A tick: its grid line across the plot, its mark and its value.
std::string svgTick(const Segment& grid, const Segment& mark, double labelX, double labelY, const char* anchor,
                    double value) {
  return svgLine("grid", grid) + svgLine("axis", mark) +
         fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"{}\">{:g}</text>\n", labelX, labelY, anchor, value);
}

// Grid lines, ticks with their values, and the axes' labels.
std::string svgAxes(const Scale& scale) {
  std::string svg;
  for (const double value : tickValues(scale.xStep, scale.xMax)) {
    const double x = scale.x(value);
    svg += svgTick({x, kTop, x, kBottom}, {x, kBottom, x, kBottom + 5}, x, kBottom + 20, "middle", value);
  }
  for (const double value : tickValues(scale.yStep, scale.yMax)) {
    const double y = scale.y(value);
    svg += svgTick({kLeft, y, kRight, y}, {kLeft - 5, y, kLeft, y}, kLeft - 8, y + 4, "end", value);
  }
  svg += svgLine("axis", {kLeft, kBottom, kRight, kBottom}) + svgLine("axis", {kLeft, kBottom, kLeft, kTop});
  svg += fmt::format(
      "\n<text class=\"label\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">frame time (ms)</text>\n"
      "<text class=\"label\" transform=\"translate(20 {}) rotate(-90)\" text-anchor=\"middle\">RMSE against the "
      "reference</text>\n",
      (kLeft + kRight) / 2, kHeight - 20, (kTop + kBottom) / 2);
  return svg;
}

// The panel a hovered point shows: its decisions, time, error, image and
// decision files.
std::string svgTip(const ReportPage& page, const PointRoles& roles, size_t i) {
  const VariantResult& r = page.results[i];
  std::vector<std::string> lines;
  for (size_t c = 0; c < page.components.size() && c < r.placements.size(); ++c) {
    lines.push_back(fmt::format("{} = {}", page.components[c], r.placements[c]));
  }
  lines.push_back(fmt::format("frame {:.3f} ms", r.frameMs));
  if (double low = 0.0, high = 0.0; intervalMs(page, r, low, high)) {
    lines.push_back(fmt::format("95% interval {:.3f}-{:.3f} ms ({} pairs)", low, high, r.time.pairs));
  }
  lines.push_back(fmt::format("RMSE {:.4g} (worst {:.4g})", r.rmse, r.worstRmse));
  if (roles.front.count(i)) lines.push_back(roles.noise.count(i) ? "front, order within noise" : "on the front");
  const auto files = page.decisionFiles.find(i);
  if (files != page.decisionFiles.end()) {
    for (const std::string& file : files->second) lines.push_back("click: " + file);
  }
  std::string svg = fmt::format(
      "<g class=\"tip\"><rect class=\"panel\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>"
      "<text x=\"{}\" y=\"{}\" class=\"label\">variant {}</text>\n",
      kPanelLeft, kTop, kPanelWidth, kBottom - kTop, kPanelLeft + 10, kTop + 22, r.index);
  double y = kTop + 44;
  for (const std::string& line : lines) {
    svg += fmt::format("<text x=\"{}\" y=\"{}\">{}</text>\n", kPanelLeft + 10, y, escapeHtml(line));
    y += 17;
  }
  const auto image = page.images.find(i);
  if (image != page.images.end()) {
    svg += fmt::format(
        "<image href=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" preserveAspectRatio=\"xMidYMin meet\"/>\n",
        escapeHtml(image->second), kPanelLeft + 10, y, kPanelWidth - 20, kBottom - y - 10);
  } else {
    svg += fmt::format("<text x=\"{}\" y=\"{}\">(images: front variants only)</text>\n", kPanelLeft + 10, y + 4);
  }
  return svg + "</g>";
}

// One point: its circle with its decisions as a title, its interval as an
// error bar on the front, a link to its decision file, and its panel.
std::string svgPoint(const ReportPage& page, const PointRoles& roles, const Scale& scale, size_t i) {
  const VariantResult& r = page.results[i];
  const bool front = roles.front.count(i) > 0;
  const bool noise = roles.noise.count(i) > 0;
  std::string svg =
      fmt::format("<g class=\"pt{}{}\" id=\"v{}\">", front ? " front" : "", noise ? " noise" : "", r.index);
  const auto files = page.decisionFiles.find(i);
  const bool linked = files != page.decisionFiles.end() && !files->second.empty();
  if (linked) svg += fmt::format("<a href=\"{}\">", escapeHtml(files->second.front()));
  double low = 0.0;
  double high = 0.0;
  if (front && intervalMs(page, r, low, high)) {
    const double y = scale.y(r.rmse);
    svg += fmt::format(
        "<path class=\"bar\" d=\"M{0:.1f} {2:.1f}H{1:.1f}M{0:.1f} {3:.1f}V{4:.1f}M{1:.1f} {3:.1f}V{4:.1f}\"/>",
        scale.x(low), scale.x(high), y, y - 4, y + 4);
  }
  svg += fmt::format(
      "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\"><title>variant {}: {}; {}; RMSE {:.4g}{}</title></circle>",
      scale.x(r.frameMs), scale.y(r.rmse), front ? 6 : 4, r.index, escapeHtml(decisionsText(page, r, ", ")),
      escapeHtml(timeText(page, r)), r.rmse, noise ? "; order within noise" : "");
  if (linked) svg += "</a>";
  return svg + svgTip(page, roles, i) + "</g>\n";
}

std::string svgPlot(const ReportPage& page) {
  const PointRoles roles = rolesOf(page);
  const Scale scale = scaleFor(page, roles);
  std::string svg = fmt::format(
      "<svg width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" role=\"img\" aria-label=\"error against "
      "frame time\">\n<rect x=\"{2}\" y=\"{3}\" width=\"{4}\" height=\"{5}\" fill=\"none\" stroke=\"#ddd\"/>\n"
      "<text x=\"{6}\" y=\"{7}\">Hover a point: its decisions</text>\n<text x=\"{6}\" y=\"{8}\">and, on the front, "
      "its image.</text>\n",
      kWidth, kHeight, kPanelLeft, kTop, kPanelWidth, kBottom - kTop, kPanelLeft + 10, kTop + 22, kTop + 40);
  svg += svgAxes(scale);
  for (size_t i = 0; i < page.results.size(); ++i) {
    if (plotted(page.results[i]) && !roles.front.count(i)) svg += svgPoint(page, roles, scale, i);
  }
  std::string line;
  for (size_t i : page.front) {
    if (!plotted(page.results[i])) continue;
    line += fmt::format("{}{:.1f},{:.1f}", line.empty() ? "" : " ", scale.x(page.results[i].frameMs),
                        scale.y(page.results[i].rmse));
  }
  svg += fmt::format("<polyline class=\"frontline\" points=\"{}\"/>\n", line);
  for (size_t i : page.front) {
    if (plotted(page.results[i])) svg += svgPoint(page, roles, scale, i);
  }
  return svg + "</svg>\n";
}

std::string decisionLinks(const ReportPage& page, size_t i) {
  std::string links;
  const auto files = page.decisionFiles.find(i);
  if (files == page.decisionFiles.end()) return links;
  for (const std::string& file : files->second) {
    links += fmt::format("{}<a href=\"{}\">{}</a>", links.empty() ? "" : " ", escapeHtml(file), escapeHtml(file));
  }
  return links;
}

std::string frontTable(const ReportPage& page) {
  const PointRoles roles = rolesOf(page);
  std::string html = "<h2>Pareto front</h2>\n<table>\n<tr><th>variant</th>";
  for (const std::string& component : page.components) html += fmt::format("<th>{}</th>", escapeHtml(component));
  html +=
      "<th>frame ms</th><th>95% interval (ms)</th><th>pairs</th><th>RMSE</th><th>worst RMSE</th><th>image</th>"
      "<th>decision file</th></tr>\n";
  for (size_t i : page.front) {
    const VariantResult& r = page.results[i];
    html += fmt::format("<tr id=\"front-{0}\"><td><a href=\"#v{0}\">{0}</a></td>", r.index);
    for (const std::string& placement : r.placements) html += fmt::format("<td>{}</td>", escapeHtml(placement));
    double low = 0.0;
    double high = 0.0;
    const bool interval = intervalMs(page, r, low, high);
    html += fmt::format("<td>{:.3f}{}</td><td>{}</td><td>{}</td><td>{:.4g}</td><td>{:.4g}</td>", r.frameMs,
                        roles.noise.count(i) ? " (within noise)" : "",
                        interval ? fmt::format("{:.3f}-{:.3f}", low, high) : "", r.time.pairs, r.rmse, r.worstRmse);
    const auto image = page.images.find(i);
    html += image == page.images.end()
                ? "<td></td>"
                : fmt::format("<td><a href=\"{0}\"><img src=\"{0}\" width=\"96\" alt=\"variant {1}\"/></a></td>",
                              escapeHtml(image->second), r.index);
    html += fmt::format("<td>{}</td></tr>\n", decisionLinks(page, i));
  }
  return html + "</table>\n";
}

std::string offTradeTable(const ReportPage& page) {
  std::string html =
      "<h2>Variants off the trade</h2>\n<p>Failed, infeasible and degenerate variants, and those with NaN or Inf "
      "pixels (infinite error): none is plotted or on the front.</p>\n";
  if (page.offTrade.empty()) return html + "<p>None.</p>\n";
  html += "<table id=\"off-trade\">\n<tr><th>variant</th><th>decisions</th><th>why</th></tr>\n";
  for (const OffTradeVariant& variant : page.offTrade) {
    const VariantResult& r = page.results[variant.result];
    html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td></tr>\n", r.index,
                        escapeHtml(decisionsText(page, r, " ")), escapeHtml(variant.reason));
  }
  return html + "</table>\n";
}

std::string stabilitySection(const ReportPage& page) {
  if (!page.showStability) return "";
  std::string html =
      "<h2>Stability</h2>\n<p>Under each extreme of the material inputs (--extremes), the component that "
      "instrumented kernels find going NaN or Inf first; also in <a href=\"stability.csv\">stability.csv</a>.</p>\n";
  if (page.stability.empty()) html += "<p>No component goes NaN or Inf.</p>\n";
  if (!page.stability.empty()) html += "<ul id=\"stability\">\n";
  for (const std::string& line : page.stability) html += fmt::format("<li>{}</li>\n", escapeHtml(line));
  if (!page.stability.empty()) html += "</ul>\n";
  for (const std::string& note : page.stabilityNotes) html += fmt::format("<p>{}</p>\n", escapeHtml(note));
  return html;
}

}  // namespace

std::string escapeHtml(std::string_view text) {
  std::string escaped;
  escaped.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      case '\'': escaped += "&#39;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

std::string renderReportHtml(const ReportPage& page) {
  std::string html = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n<title>{0}</title>\n"
      "<style>{1}</style>\n</head>\n<body>\n<h1>{0}</h1>\n<p>{2}</p>\n"
      "<p>The same run as <a href=\"report.md\">report.md</a>; every variant in <a href=\"variants.csv\">"
      "variants.csv</a>, the front in <a href=\"pareto.csv\">pareto.csv</a>.</p>\n<h2>Error against frame time</h2>\n"
      "<p><span class=\"key other\"></span>variant<span class=\"key front\"></span>on the Pareto front, with its 95% "
      "time interval<span class=\"key noise\"></span>on the front, its order against a neighbour within the noise "
      "(their intervals overlap)</p>\n",
      escapeHtml(page.title), kStyle, escapeHtml(page.summary));
  html += svgPlot(page);
  html += frontTable(page);
  html += offTradeTable(page);
  html += stabilitySection(page);
  return html + "</body>\n</html>\n";
}

}  // namespace spire::tune
