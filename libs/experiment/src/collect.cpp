#include "roadslam/experiment/collect.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "roadslam/common/atomic_file.h"
#include "roadslam/experiment/run_job.h"
#include "roadslam/report/html_page.h"
#include "roadslam/report/svg_plot.h"

namespace fs = std::filesystem;

namespace roadslam::experiment {
namespace {

std::optional<nlohmann::json> tryJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::string tail(const std::string& path, size_t lines) {
  std::ifstream in(path);
  std::vector<std::string> all;
  for (std::string l; std::getline(in, l);) all.push_back(l);
  std::string out;
  for (size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) out += all[i] + "\n";
  return out;
}

std::string cell(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_number_float()) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", v.get<double>());
    return b;
  }
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// Per metric, the variant with the best mean over the datasets, among the variants whose every
/// job succeeded and reported the metric.
nlohmann::json bestPerMetric(const nlohmann::json& rows) {
  std::map<size_t, std::vector<const nlohmann::json*>> by_variant;
  for (const auto& r : rows) by_variant[r["variant"].get<size_t>()].push_back(&r);
  nlohmann::json best = nlohmann::json::object();
  for (const auto& mi : metricInfos()) {
    double best_v = 0;
    long best_var = -1;
    for (const auto& [v, rs] : by_variant) {
      double sum = 0;
      bool all = true;
      for (const auto* r : rs) {
        const auto& m = (*r)["metrics"];
        if ((*r)["status"] != "ok" || !m.contains(mi.name) || !m[mi.name].is_number()) all = false;
        else sum += m[mi.name].get<double>();
      }
      if (!all || rs.empty()) continue;
      const double mean = sum / static_cast<double>(rs.size());
      if (best_var < 0 || (mi.lower_is_better ? mean < best_v : mean > best_v)) best_v = mean, best_var = static_cast<long>(v);
    }
    if (best_var >= 0) {
      best[mi.name] = {{"variant", best_var}, {"mean", best_v}, {"params", (*by_variant[best_var].front())["params"]}};
    }
  }
  return best;
}

void writeCsv(const std::string& path, const nlohmann::json& rows, const std::vector<std::string>& swept,
              const std::vector<std::string>& metrics) {
  std::string csv = "index,variant,dataset";
  for (const auto& p : swept) csv += "," + csvField(p);
  csv += ",status";
  for (const auto& m : metrics) csv += "," + m;
  csv += ",reason,dir\n";
  for (const auto& r : rows) {
    csv += std::to_string(r["index"].get<size_t>()) + "," + std::to_string(r["variant"].get<size_t>()) + "," +
           csvField(r["dataset"]);
    for (const auto& p : swept) csv += "," + csvField(r["params"].value(p, ""));
    csv += "," + r["status"].get<std::string>();
    for (const auto& m : metrics) csv += "," + cell(r["metrics"].contains(m) ? r["metrics"][m] : nlohmann::json());
    csv += "," + csvField(r.value("reason", "")) + "," + csvField(r["dir"]) + "\n";
  }
  writeFileAtomically(path, csv);
}

void writeReport(const std::string& out_dir, const nlohmann::json& plan, const nlohmann::json& res,
                 const std::vector<std::string>& swept, const std::vector<std::string>& metrics) {
  report::HtmlPage page("roadslam experiment: " + plan.value("experiment", std::string("?")));
  const auto& rows = res["jobs"];
  page.paragraph("Experiment file " + plan.value("spec", std::string("?")) + ", base config " +
                 plan.value("base_config", std::string("?")) + ". Jobs: " + std::to_string(res["counts"]["jobs"].get<size_t>()) +
                 ", ok " + std::to_string(res["counts"]["ok"].get<size_t>()) + ", failed " +
                 std::to_string(res["counts"]["failed"].get<size_t>()) + ", not run " +
                 std::to_string(res["counts"]["missing"].get<size_t>()) + ".");
  page.heading("Best configuration per metric (mean over the datasets)");
  std::vector<std::vector<std::string>> best_rows;
  for (const auto& mi : metricInfos()) {
    if (!res["best"].contains(mi.name)) continue;
    const auto& b = res["best"][mi.name];
    std::string params;
    for (const auto& [k, v] : b["params"].items()) params += (params.empty() ? "" : ", ") + k + " = " + v.get<std::string>();
    best_rows.push_back({std::string(mi.name) + (mi.lower_is_better ? " (lower is better)" : " (higher is better)"),
                         cell(b["mean"]), std::to_string(b["variant"].get<long>()), params.empty() ? "(base)" : params});
  }
  page.table({"metric", "best mean", "variant", "parameters"}, best_rows);
  // Each metric against the first swept parameter, when its values are numbers: one series per dataset.
  if (!swept.empty()) {
    std::map<std::string, std::vector<const nlohmann::json*>> by_dataset;
    for (const auto& r : rows) by_dataset[r["dataset"]].push_back(&r);
    for (const auto& m : metrics) {
      std::vector<report::Series> series;
      for (const auto& [ds, rs] : by_dataset) {
        report::Series s{ds, {}, {}};
        for (const auto* r : rs) {
          const std::string v = (*r)["params"].value(swept.front(), "");
          char* end = nullptr;
          const double x = std::strtod(v.c_str(), &end);
          if (end == v.c_str() || *end || (*r)["status"] != "ok" || !(*r)["metrics"].contains(m)) continue;
          s.x.push_back(x), s.y.push_back((*r)["metrics"][m].get<double>());
        }
        if (s.x.empty()) continue;
        std::vector<size_t> order(s.x.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return s.x[a] < s.x[b]; });
        report::Series sorted{ds, {}, {}};
        for (size_t i : order) sorted.x.push_back(s.x[i]), sorted.y.push_back(s.y[i]);
        series.push_back(sorted);
      }
      if (series.empty()) continue;
      report::PlotOptions o;
      o.title = m + " against " + swept.front();
      o.x_label = swept.front(), o.y_label = m;
      page.svg(report::svgPlot(series, o));
    }
  }
  page.heading("Every job");
  std::vector<std::string> header = {"#", "dataset"};
  for (const auto& p : swept) header.push_back(p);
  header.push_back("status");
  for (const auto& m : metrics) header.push_back(m);
  std::vector<std::vector<std::string>> table;
  for (const auto& r : rows) {
    std::vector<std::string> t = {std::to_string(r["index"].get<size_t>()), r["dataset"]};
    for (const auto& p : swept) t.push_back(r["params"].value(p, ""));
    t.push_back(r["status"]);
    for (const auto& m : metrics) t.push_back(cell(r["metrics"].contains(m) ? r["metrics"][m] : nlohmann::json()));
    table.push_back(t);
  }
  page.table(header, table);
  bool any_failed = false;
  for (const auto& r : rows) {
    if (r["status"] != "failed") continue;
    if (!any_failed) page.heading("Failed jobs");
    any_failed = true;
    page.paragraph("#" + std::to_string(r["index"].get<size_t>()) + " " + r["dataset"].get<std::string>() + " (" +
                   r["dir"].get<std::string>() + "): " + r.value("reason", ""));
    page.code(tail(out_dir + "/" + r["dir"].get<std::string>() + "/log.txt", 20));
  }
  page.write(out_dir + "/report.html");
}

}  // namespace

Collected collect(const std::string& out_dir) {
  const auto plan = tryJson(out_dir + "/plan.json");
  if (!plan) throw std::runtime_error("'" + out_dir + "/plan.json' is missing or unreadable: not an experiment folder");
  std::vector<std::string> swept = (*plan)["swept"].get<std::vector<std::string>>();
  Collected c;
  nlohmann::json rows = nlohmann::json::array();
  std::set<std::string> seen_metrics;
  for (const auto& j : (*plan)["jobs"]) {
    const std::string dir = out_dir + "/" + j["dir"].get<std::string>();
    nlohmann::json r = {{"index", j["index"]}, {"variant", j["variant"]}, {"dataset", j["dataset"]},
                        {"params", j["params"]}, {"dir", j["dir"]}, {"metrics", nlohmann::json::object()}};
    const auto m = tryJson(dir + "/metrics.json");
    const auto f = tryJson(dir + "/failed.json");
    if (m && m->value("key", "") == j["key"]) {
      r["status"] = "ok";
      for (const auto& [k, v] : m->items()) {
        if (v.is_number()) r["metrics"][k] = v, seen_metrics.insert(k);
      }
      ++c.ok;
    } else if (f && f->value("key", "") == j["key"]) {
      r["status"] = "failed", r["reason"] = f->value("reason", "");
      ++c.failed;
    } else {
      r["status"] = "missing";
      ++c.missing;
    }
    ++c.jobs;
    rows.push_back(r);
  }
  std::vector<std::string> metrics;
  for (const auto& mi : metricInfos()) {
    if (seen_metrics.count(mi.name)) metrics.push_back(mi.name);
  }
  c.results = {{"experiment", (*plan)["experiment"]}, {"swept", swept}, {"metrics", metrics},
               {"counts", {{"jobs", c.jobs}, {"ok", c.ok}, {"failed", c.failed}, {"missing", c.missing}}},
               {"jobs", rows}, {"best", bestPerMetric(rows)}};
  writeFileAtomically(out_dir + "/results.json", c.results.dump(2) + "\n");
  writeCsv(out_dir + "/results.csv", rows, swept, metrics);
  writeReport(out_dir, *plan, c.results, swept, metrics);
  return c;
}

}  // namespace roadslam::experiment
