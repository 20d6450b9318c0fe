#include "tune/results_csv.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace spire::tune {

namespace {

constexpr const char* kTrailing[] = {"status",  "frame_ms",      "first_frame_ms", "prebake_ms",    "rmse",
                                     "psnr",    "max_error",     "nan_pixels",     "inf_pixels",    "same_as",
                                     "kernels", "hazard_inputs", "time_ratio",     "ratio_low",     "ratio_high",
                                     "pairs",   "worst_rmse",    "hazard_causes",  "hazard_samples"};

}  // namespace

std::string quoteCsv(const std::string& field) {
  if (field.find_first_of(",\"\n") == std::string::npos) return field;
  std::string quoted = "\"";
  for (char c : field) quoted += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return quoted + "\"";
}

namespace {

std::string number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{:.9g}", value);
}

std::optional<double> parseNumber(const std::string& text) {
  if (text == "nan") return std::nan("");
  if (text == "inf") return std::numeric_limits<double>::infinity();
  if (text == "-inf") return -std::numeric_limits<double>::infinity();
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::optional<uint64_t> parseCount(const std::string& text) {
  uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// "S@V;S@V": each hazardous parameter sample with its first hazardous view.
std::string samplesText(const std::vector<std::pair<size_t, size_t>>& samples) {
  std::string text;
  for (const auto& [sample, view] : samples) text += fmt::format("{}{}@{}", text.empty() ? "" : ";", sample, view);
  return text;
}

std::optional<std::vector<std::pair<size_t, size_t>>> parseSamples(const std::string& text) {
  std::vector<std::pair<size_t, size_t>> samples;
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find(';', start), text.size());
    const std::string item = text.substr(start, end - start);
    const size_t at = item.find('@');
    if (at == std::string::npos) return std::nullopt;
    const auto sample = parseCount(item.substr(0, at));
    const auto view = parseCount(item.substr(at + 1));
    if (!sample || !view) return std::nullopt;
    samples.emplace_back(*sample, *view);
    start = end + 1;
  }
  return samples;
}

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

}  // namespace

std::string csvHeader(const std::vector<std::string>& components) {
  std::string header = "index";
  for (const std::string& c : components) header += "," + quoteCsv(c);
  for (const char* column : kTrailing) header += std::string(",") + column;
  return header + "\n";
}

std::string csvRow(const VariantResult& r) {
  std::string row = std::to_string(r.index);
  for (const std::string& p : r.placements) row += "," + quoteCsv(p);
  row += fmt::format(",{},{},{},{},{},{},{},{},{},{},{},{}\n", quoteCsv(r.status), number(r.frameMs),
                     number(r.firstFrameMs), number(r.prebakeMs), number(r.rmse), number(r.psnr), number(r.maxError),
                     r.nanPixels, r.infPixels, r.sameAs ? std::to_string(*r.sameAs) : "", quoteCsv(r.kernels),
                     quoteCsv(r.hazardInputs));
  row.pop_back();  // the newline, after the columns below
  row += fmt::format(",{},{},{},{},{},{},{}\n", number(r.time.median), number(r.time.interval.low),
                     number(r.time.interval.high), r.time.pairs, number(r.worstRmse),
                     quoteCsv(fmt::format("{}", fmt::join(r.hazardCauses, " | "))), samplesText(r.hazardSamples));
  return row;
}

namespace {

// The columns an older spire-tune's table lacks: its header ends with a
// proper prefix of today's trailing columns (each version added columns at
// the end). Empty when the header is not such a table.
std::vector<std::string> missingTrailing(const std::vector<std::string>& fields) {
  for (size_t kept = std::size(kTrailing) - 1; kept > 0; --kept) {
    if (fields.size() <= kept || fields.front() != "index") continue;
    if (std::equal(std::begin(kTrailing), std::begin(kTrailing) + static_cast<std::ptrdiff_t>(kept),
                   fields.end() - static_cast<std::ptrdiff_t>(kept))) {
      return std::vector<std::string>(std::begin(kTrailing) + static_cast<std::ptrdiff_t>(kept), std::end(kTrailing));
    }
  }
  return {};
}

// An older table's measurements were taken and recorded differently (the
// columns it lacks are what changed), so it is named, never mixed in.
Failure olderTable(const std::filesystem::path& path, const std::vector<std::string>& missing) {
  return Failure{fmt::format(
      "{}: written by an older spire-tune (it has no column {}); its rows cannot be resumed: remove it or choose "
      "another output directory",
      path.string(), fmt::join(missing, ", "))};
}

}  // namespace

Expected<std::vector<std::string>, Failure> readComponents(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) return Failure{fmt::format("cannot read '{}'", path.string())};
  const std::vector<std::string> fields = splitCsv(line);
  const size_t trailing = std::size(kTrailing);
  const bool tail = fields.size() > trailing && std::equal(std::begin(kTrailing), std::end(kTrailing),
                                                           fields.end() - static_cast<std::ptrdiff_t>(trailing));
  if (const std::vector<std::string> missing = missingTrailing(fields); !missing.empty()) {
    return olderTable(path, missing);
  }
  if (fields.empty() || fields.front() != "index" || !tail) {
    return Failure{fmt::format("{}: not a spire-tune table (its header is not the tuner's)", path.string())};
  }
  return std::vector<std::string>(fields.begin() + 1, fields.end() - static_cast<std::ptrdiff_t>(trailing));
}

Expected<std::vector<VariantResult>, Failure> readResults(const std::filesystem::path& path,
                                                          const std::vector<std::string>& components) {
  std::ifstream in(path);
  std::vector<VariantResult> results;
  if (!in) return results;
  std::string line;
  if (!std::getline(in, line)) return results;
  if (line + "\n" != csvHeader(components)) {
    const std::vector<std::string> missing = missingTrailing(splitCsv(line));
    if (!missing.empty()) return olderTable(path, missing);
    return Failure{fmt::format(
        "{}: written by a run over other components; remove it or choose another output directory", path.string())};
  }
  const size_t expected = 1 + components.size() + std::size(kTrailing);
  for (size_t lineNumber = 2; std::getline(in, line); ++lineNumber) {
    if (line.empty()) continue;
    const std::vector<std::string> f = splitCsv(line);
    // A row cut short by an interruption is dropped: its variant runs again.
    if (f.size() != expected) continue;
    VariantResult r;
    const auto index = parseCount(f[0]);
    size_t i = 1 + components.size();
    const auto frame = parseNumber(f[i + 1]);
    const auto first = parseNumber(f[i + 2]);
    const auto prebake = parseNumber(f[i + 3]);
    const auto rmse = parseNumber(f[i + 4]);
    const auto psnr = parseNumber(f[i + 5]);
    const auto maxError = parseNumber(f[i + 6]);
    const auto nan = parseCount(f[i + 7]);
    const auto inf = parseCount(f[i + 8]);
    const auto ratio = parseNumber(f[i + 12]);
    const auto low = parseNumber(f[i + 13]);
    const auto high = parseNumber(f[i + 14]);
    const auto pairs = parseCount(f[i + 15]);
    const auto worst = parseNumber(f[i + 16]);
    const auto hazardSamples = parseSamples(f[i + 18]);
    for (size_t start = 0; start < f[i + 17].size();) {
      const size_t end = std::min(f[i + 17].find(" | ", start), f[i + 17].size());
      r.hazardCauses.push_back(f[i + 17].substr(start, end - start));
      start = end + 3;
    }
    if (!index || !frame || !first || !prebake || !rmse || !psnr || !maxError || !nan || !inf || !ratio || !low ||
        !high || !pairs || !worst || !hazardSamples) {
      return Failure{fmt::format("{}:{}: malformed row", path.string(), lineNumber)};
    }
    r.index = *index;
    r.placements.assign(f.begin() + 1, f.begin() + 1 + static_cast<std::ptrdiff_t>(components.size()));
    r.status = f[i];
    r.frameMs = *frame;
    r.firstFrameMs = *first;
    r.prebakeMs = *prebake;
    r.rmse = *rmse;
    r.psnr = *psnr;
    r.maxError = *maxError;
    r.nanPixels = *nan;
    r.infPixels = *inf;
    if (!f[i + 9].empty()) r.sameAs = parseCount(f[i + 9]);
    r.kernels = f[i + 10];
    r.hazardInputs = f[i + 11];
    r.time = {*ratio, {*low, *high}, static_cast<uint32_t>(*pairs)};
    r.worstRmse = *worst;
    r.hazardSamples = *hazardSamples;
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace spire::tune
