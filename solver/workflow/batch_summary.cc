#include "solver/workflow/batch_summary.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <system_error>

#include <fmt/core.h>

#include "hb/csv_cell.h"
#include "hb/errors.h"
#include "hb/text_file.h"
#include "solver/estimation/damping_laws.h"
#include "solver/estimation/result_io.h"
#include "solver/report/html_escape.h"
#include "solver/report/html_page.h"

namespace beamid::workflow {
namespace {

namespace fs = std::filesystem;

// The parameters the report draws as the answer: under the fitted law when
// the data accept it (or the laws were not refitted), else under the
// accepted law of least χ².
void TakeAnswer(const solver::ResultFile& result, BatchRow& row) {
  const solver::DampingLawFit* answer = solver::AnswerLaw(result.damping_laws);
  const bool other_law = answer != nullptr && answer != &result.damping_laws.laws.front();
  if (other_law) {
    for (const solver::ParameterEstimate& p : answer->parameters)
      row.parameters.push_back({p.name, p.unit, p.value, p.std, p.lower_95, p.upper_95});
    row.damping_law = answer->law;
    row.reduced_chi_square = answer->reduced_chi_square;
  } else {
    for (const solver::ResultParameter& p : result.parameters)
      row.parameters.push_back({p.name, p.unit, p.value, p.std, p.lower_95, p.upper_95});
    row.damping_law = result.damping_laws.laws.empty() ? "" : result.damping_laws.laws.front().law;
    row.reduced_chi_square = result.fit.reduced_chi_square;
  }
  row.within_noise = result.fit.verdict.within_noise;
  row.verdict = result.fit.verdict.text;
}

// Every parameter any row holds, in the order they first appear.
std::vector<std::pair<std::string, std::string>> ParameterColumns(const BatchSummary& summary) {
  std::vector<std::pair<std::string, std::string>> columns;
  for (const BatchRow& row : summary.rows)
    for (const BatchParameter& p : row.parameters)
      if (std::none_of(columns.begin(), columns.end(), [&](const auto& c) { return c.first == p.name; }))
        columns.emplace_back(p.name, p.unit);
  return columns;
}

const BatchParameter* Find(const BatchRow& row, const std::string& name) {
  const auto it = std::find_if(row.parameters.begin(), row.parameters.end(),
                               [&](const BatchParameter& p) { return p.name == name; });
  return it == row.parameters.end() ? nullptr : &*it;
}

std::string_view StatusName(BatchStatus status) { return schema::NameOf(status, kBatchStatusNames); }

// A file an entry names lies in the entry's own folder: a name, never a path
// (a batch.json from elsewhere must not make the summary read or link
// another file).
void CheckFileName(const fs::path& entry_file, const std::string& key, const std::string& name) {
  if (name.empty()) return;
  if (name.find('/') != std::string::npos || name.starts_with("."))
    throw InputError(fmt::format("{}: {} '{}' is not a file name in the entry's folder; run 'beamid batch' again on "
                                 "that campaign", entry_file.string(), key, name));
}

}  // namespace

int BatchSummary::Count(BatchStatus status) const {
  return static_cast<int>(std::count_if(rows.begin(), rows.end(),
                                        [&](const BatchRow& row) { return row.entry.status == status; }));
}

BatchSummary CollectBatch(const fs::path& output_folder) {
  BatchSummary summary;
  std::error_code error;
  if (!fs::is_directory(output_folder, error))
    throw InputError(output_folder.string() + " is no folder: give the output folder of 'beamid batch'");
  std::vector<fs::path> folders;
  for (const fs::directory_entry& item : fs::directory_iterator(output_folder, error))
    if (item.is_directory(error) && fs::is_regular_file(item.path() / kBatchEntryFileName, error))
      folders.push_back(item.path());
  std::sort(folders.begin(), folders.end());
  for (const fs::path& folder : folders) {
    BatchRow row{.folder = folder.filename().string(), .entry = {}, .parameters = {}, .damping_law = {},
                 .reduced_chi_square = std::numeric_limits<double>::quiet_NaN(), .within_noise = false,
                 .verdict = {}};
    try {
      row.entry = ReadBatchEntry(folder / kBatchEntryFileName);
      for (const auto& [key, name] : {std::pair{"result_file", row.entry.result_file},
                                      std::pair{"report_file", row.entry.report_file},
                                      std::pair{"errors_file", row.entry.errors_file}})
        CheckFileName(folder / kBatchEntryFileName, key, name);
      if (!row.entry.result_file.empty()) TakeAnswer(solver::ReadResultFile(folder / row.entry.result_file), row);
    } catch (const InputError& e) {
      summary.warnings.push_back(fmt::format("{}: left out of the summary: {}", folder.string(), e.what()));
      continue;
    }
    summary.rows.push_back(std::move(row));
  }
  return summary;
}

std::string BatchSummaryCsv(const BatchSummary& summary) {
  using hb::CsvNumber;
  using hb::CsvText;
  const auto columns = ParameterColumns(summary);
  std::string csv =
      "folder,campaign,campaign_name,status,exit_code,seconds,damping_law,reduced_chi_square,within_noise";
  for (const auto& [name, unit] : columns)
    csv += fmt::format(",{0},{1},{2},{3}", CsvText(name + " [" + unit + "]"), CsvText(name + " std [" + unit + "]"),
                       CsvText(name + " lower_95 [" + unit + "]"), CsvText(name + " upper_95 [" + unit + "]"));
  csv += ",verdict,message,report\n";
  for (const BatchRow& row : summary.rows) {
    const BatchEntry& e = row.entry;
    const bool fitted = !row.parameters.empty();
    csv += fmt::format("{},{},{},{},{},{},{},{},{}", CsvText(row.folder), CsvText(e.campaign),
                       CsvText(e.campaign_name), StatusName(e.status), e.exit_code, CsvNumber(e.seconds, "{:.3f}"),
                       CsvText(row.damping_law), CsvNumber(row.reduced_chi_square, "{:.6g}"),
                       fitted ? (row.within_noise ? "1" : "0") : "");
    for (const auto& column : columns) {
      const BatchParameter* p = Find(row, column.first);
      if (p == nullptr)
        csv += ",,,,";
      else
        csv += fmt::format(",{},{},{},{}", CsvNumber(p->value, "{:.9g}"), CsvNumber(p->std, "{:.3g}"),
                           CsvNumber(p->lower_95, "{:.9g}"), CsvNumber(p->upper_95, "{:.9g}"));
    }
    const std::string report = e.report_file.empty() ? "" : row.folder + "/" + e.report_file;
    csv += fmt::format(",{},{},{}\n", CsvText(row.verdict), CsvText(e.message), CsvText(report));
  }
  return csv;
}

std::string BatchIndexHtml(const BatchSummary& summary, const std::string& title) {
  using solver::HtmlEscape;
  const auto columns = ParameterColumns(summary);
  std::string html = solver::HtmlPageHead(title);
  html += fmt::format("<p>{} campaigns: {} fitted within their noise, {} fitted beyond it (run <code>beamid diagnose"
                      "</code> on them), {} failed. The parameters are those the report gives as the answer, with σ "
                      "and the 95 % interval. The same table: <a href=\"{}\">{}</a>.</p>\n",
                      summary.rows.size(), summary.Count(BatchStatus::kFitted), summary.Count(BatchStatus::kMisfit),
                      summary.Count(BatchStatus::kFailed), kBatchSummaryCsv, kBatchSummaryCsv);
  html += "<table>\n<tr><th>campaign</th><th>status</th>";
  for (const auto& [name, unit] : columns)
    html += fmt::format("<th>{} [{}]<br>(95 %)</th>", HtmlEscape(name), HtmlEscape(unit));
  html += "<th>reduced χ²</th><th>damping law</th><th>verdict or error</th><th>time [s]</th></tr>\n";
  for (const BatchRow& row : summary.rows) {
    const BatchEntry& e = row.entry;
    const std::string name = HtmlEscape(e.campaign_name.empty() ? row.folder : e.campaign_name);
    const std::string link =
        e.report_file.empty()
            ? name
            : fmt::format("<a href=\"{}\">{}</a>", HtmlEscape(row.folder + "/" + e.report_file), name);
    // A fit beyond the noise and a failure stand out where the number is shown.
    html += fmt::format("<tr{}><td title=\"{}\">{}</td><td>{}</td>",
                        e.status == BatchStatus::kFitted ? "" : " class=\"flag\"", HtmlEscape(e.campaign), link,
                        StatusName(e.status));
    for (const auto& column : columns) {
      const BatchParameter* p = Find(row, column.first);
      html += p == nullptr ? std::string("<td></td>")
                           : fmt::format("<td>{:.6g} ± {:.2g}<br>({:.6g} … {:.6g})</td>", p->value, p->std,
                                         p->lower_95, p->upper_95);
    }
    const std::string said = e.status == BatchStatus::kFailed ? e.message : row.verdict;
    html += fmt::format("<td>{}</td><td>{}</td><td>{}{}</td><td>{:.1f}</td></tr>\n",
                        std::isfinite(row.reduced_chi_square) ? fmt::format("{:.3g}", row.reduced_chi_square) : "",
                        HtmlEscape(row.damping_law), HtmlEscape(said),
                        e.report_problem.empty() ? "" : "<br>no report: " + HtmlEscape(e.report_problem), e.seconds);
  }
  html = solver::ScrollableTables(html + "</table>\n");
  for (const std::string& w : summary.warnings) html += "<p class=\"warning\">" + HtmlEscape(w) + "</p>\n";
  html += "</body>\n</html>\n";
  return html;
}

void WriteBatchSummary(const fs::path& output_folder, const BatchSummary& summary) {
  WriteTextFileAtomically(output_folder / kBatchSummaryCsv, BatchSummaryCsv(summary));
  WriteTextFileAtomically(output_folder / kBatchIndexHtml,
                          BatchIndexHtml(summary, "beamid batch: " + output_folder.filename().string()));
}

}  // namespace beamid::workflow
