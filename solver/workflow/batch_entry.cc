#include "solver/workflow/batch_entry.h"

#include "hb/text_file.h"

namespace beamid::workflow {
namespace {

constexpr schema::Format kBatchEntrySchema{kBatchEntryFormat, "batch entry",
                                           "give the batch.json 'beamid batch' wrote in a campaign's folder"};

}  // namespace

void Describe(auto& io, schema::Like<BatchEntry> auto& e) {
  io.Constant("format", kBatchEntryFormat);
  io.Text("beamid_version", e.beamid_version);
  io.Text("campaign", e.campaign, schema::TextRule::kNotEmpty);
  io.Text("campaign_name", e.campaign_name);
  io.Choice("status", e.status, kBatchStatusNames);
  io.Integer("exit_code", e.exit_code, 0, 255);
  io.Text("message", e.message);
  io.Number("seconds", e.seconds, "s", schema::NonNegative());
  io.Text("result_file", e.result_file);
  io.Text("report_file", e.report_file);
  io.Text("report_problem", e.report_problem);
  io.Text("errors_file", e.errors_file);
}

std::vector<schema::FieldDoc> BatchEntryFields() { return schema::Fields<BatchEntry>(); }

void WriteBatchEntry(const std::filesystem::path& file, const BatchEntry& entry) {
  WriteTextFileAtomically(file, schema::ToJson(entry));
}

BatchEntry BatchEntryFromJson(const std::string& text, const std::string& source) {
  return schema::FromJson<BatchEntry>(text, source, kBatchEntrySchema);
}

BatchEntry ReadBatchEntry(const std::filesystem::path& file) {
  return BatchEntryFromJson(ReadTextFile(file, "batch entry", "run 'beamid batch' again on that campaign"),
                            file.string());
}

}  // namespace beamid::workflow
