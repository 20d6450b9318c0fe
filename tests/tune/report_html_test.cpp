// report.html from synthetic tuner results: well-formed, one circle per
// plotted variant, the front and the points within the noise marked, text
// escaped, nothing fetched from elsewhere, and the variants off the trade
// listed with their reasons.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "tune/report_html.h"

namespace spire::tune {
namespace {

size_t count(std::string_view text, std::string_view what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string_view::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// Every tag of `html` closes, in order (the page writes void elements as
// <x/>); the first mismatch, or empty when there is none.
std::string unbalancedTag(std::string_view html) {
  std::vector<std::string> open;
  for (size_t at = html.find('<'); at != std::string_view::npos; at = html.find('<', at + 1)) {
    const size_t end = html.find('>', at);
    if (end == std::string_view::npos) return "a tag that does not end at " + std::to_string(at);
    const std::string_view tag = html.substr(at + 1, end - at - 1);
    if (tag.starts_with("!")) continue;
    const bool closing = tag.starts_with("/");
    const std::string_view body = closing ? tag.substr(1) : tag;
    const std::string name(body.substr(0, body.find_first_of(" \t\n/")));
    if (closing) {
      if (open.empty() || open.back() != name)
        return "</" + name + "> closes " + (open.empty() ? "nothing" : open.back());
      open.pop_back();
    } else if (!tag.ends_with("/")) {
      open.push_back(name);
    }
  }
  return open.empty() ? "" : "<" + open.back() + "> never closes";
}

VariantResult variant(uint64_t index, std::vector<std::string> placements, double ms, double rmse, double low,
                      double high) {
  VariantResult r;
  r.index = index;
  r.placements = std::move(placements);
  r.frameMs = ms;
  r.rmse = rmse;
  r.worstRmse = rmse * 1.5;
  r.time = {ms / 2.0, {low / 2.0, high / 2.0}, 9};  // the reference's frame is 2 ms
  return r;
}

// Four measured variants (three on the front, two of them within the noise
// of each other), a failed one and one with NaN pixels.
struct Synthetic {
  std::vector<VariantResult> results;
  ReportPage page;

  Synthetic() {
    results.push_back(variant(0, {"Fragment", "Fragment:ggx"}, 2.0, 0.0, 1.96, 2.04));
    results.push_back(variant(1, {"Vertex", "Rock<LodMQ> & Co"}, 1.0, 0.02, 0.98, 1.02));
    results.push_back(variant(2, {"PrebakeTex", "Fragment:basic"}, 1.03, 0.01, 1.01, 1.06));
    results.push_back(variant(3, {"Vertex", "Vertex:ggx"}, 2.5, 0.03, 2.4, 2.6));
    VariantResult failed = variant(4, {"Fragment", "Vertex:basic"}, 0.0, 0.0, 0.0, 0.0);
    failed.status = "failed: 'x' : undeclared identifier <here>";
    results.push_back(failed);
    VariantResult hazard = variant(5, {"Vertex", "Fragment:ggx"}, 1.5, 0.0, 1.4, 1.6);
    hazard.nanPixels = 12;
    hazard.rmse = std::numeric_limits<double>::infinity();
    results.push_back(hazard);

    page.title = "spire-tune report: Terrain on terrain.json";
    page.summary = "A run of <6> variants & more";
    page.components = {"albedo", "lighting"};
    page.results = results;
    page.front = {1, 2, 0};
    page.referenceMs = 2.0;
    for (size_t i : page.front) page.images[i] = "front/" + std::to_string(results[i].index) + ".png";
    page.decisionFiles[2].push_back("best_time_budget.decisions");
    page.decisionFiles[0].push_back("best_error_budget.decisions");
    page.offTrade = {{4, failed.status}, {5, "12 NaN and 0 Inf pixels, first under camera view 0"}};
  }
};

TEST(ReportHtml, IsWellFormedWithOneCirclePerPlottedVariant) {
  const Synthetic run;
  const std::string html = renderReportHtml(run.page);
  EXPECT_TRUE(html.starts_with("<!DOCTYPE html>")) << html.substr(0, 40);
  EXPECT_EQ(unbalancedTag(html), "") << html;
  EXPECT_EQ(count(html, "<svg"), 1U);
  // Failed and hazardous variants are not plotted.
  EXPECT_EQ(count(html, "<circle"), 4U) << html;
  EXPECT_EQ(count(html, "<polyline class=\"frontline\""), 1U);
  EXPECT_EQ(count(html, "<script"), 0U);
  EXPECT_EQ(count(html, "http://"), 0U);
  EXPECT_EQ(count(html, "https://"), 0U);
}

TEST(ReportHtml, MarksTheFrontAndThePointsWithinTheNoise) {
  const Synthetic run;
  const std::string html = renderReportHtml(run.page);
  EXPECT_EQ(count(html, "class=\"pt front"), 3U) << html;
  // Variants 1 and 2 overlap in time: their order is within the noise.
  EXPECT_EQ(count(html, "class=\"pt front noise\""), 2U) << html;
  EXPECT_NE(html.find("<g class=\"pt front noise\" id=\"v1\">"), std::string::npos) << html;
  EXPECT_NE(html.find("<g class=\"pt front noise\" id=\"v2\">"), std::string::npos) << html;
  EXPECT_NE(html.find("<g class=\"pt front\" id=\"v0\">"), std::string::npos) << html;
  EXPECT_NE(html.find("<g class=\"pt\" id=\"v3\">"), std::string::npos) << html;
  // Every front point has its interval as an error bar.
  EXPECT_EQ(count(html, "<path class=\"bar\""), 3U) << html;
  // The front's images show on hover and in the table; the decision files
  // are linked.
  EXPECT_EQ(count(html, "<image href=\"front/"), 3U) << html;
  EXPECT_NE(html.find("<img src=\"front/1.png\""), std::string::npos) << html;
  EXPECT_NE(html.find("<a href=\"best_time_budget.decisions\">"), std::string::npos) << html;
  EXPECT_NE(html.find("<a href=\"best_error_budget.decisions\">"), std::string::npos) << html;
}

TEST(ReportHtml, EscapesTextAndListsTheVariantsOffTheTrade) {
  const Synthetic run;
  const std::string html = renderReportHtml(run.page);
  EXPECT_NE(html.find("Rock&lt;LodMQ&gt; &amp; Co"), std::string::npos) << html;
  EXPECT_EQ(html.find("Rock<LodMQ>"), std::string::npos) << html;
  EXPECT_NE(html.find("A run of &lt;6&gt; variants &amp; more"), std::string::npos) << html;
  EXPECT_NE(html.find("<table id=\"off-trade\">"), std::string::npos) << html;
  EXPECT_NE(html.find("<tr><td>4</td><td>albedo=Fragment lighting=Vertex:basic</td><td>failed: &#39;x&#39; : "
                      "undeclared identifier &lt;here&gt;</td></tr>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<tr><td>5</td><td>albedo=Vertex lighting=Fragment:ggx</td><td>12 NaN and 0 Inf pixels"),
            std::string::npos)
      << html;
  EXPECT_EQ(escapeHtml("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&#39;");
}

}  // namespace
}  // namespace spire::tune
