// The evaluation's building blocks: result tables, the experiment registry and its errors.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/util/Error.h"
#include "eval/CsvTable.h"
#include "eval/PaperEvaluation.h"

using namespace mfadvr;
using namespace mfadvr::eval;

TEST(CsvTable, QuotesFieldsThatNeedItAndRejectsRaggedRows) {
  CsvTable t({"name", "value"});
  t.addRow({"plain", "1"});
  t.addRow({"a,b", "say \"hi\""});
  EXPECT_EQ(t.toCsv(), "name,value\nplain,1\n\"a,b\",\"say \"\"hi\"\"\"\n");
  EXPECT_THROW(t.addRow({"only one"}), Error);
  EXPECT_EQ(t.columnIndex("value"), 1u);
  EXPECT_THROW(t.columnIndex("missing"), Error);
}

TEST(CsvTable, MarkdownSelectsAndRelabelsColumns) {
  CsvTable t({"a", "b", "c"});
  t.addRow({"1", "x|y", "3"});
  EXPECT_EQ(t.toMarkdown({"c", "b"}, {"C", "B"}), "| C | B |\n|---|---|\n| 3 | x/y |\n");
  EXPECT_THROW(t.toMarkdown({"a"}, {"A", "B"}), Error);
}

TEST(CsvTable, NumbersPrintAlike) {
  EXPECT_EQ(csvNumber(1.0 / 0.0), "inf");
  EXPECT_EQ(csvNumber(-1.0 / 0.0), "-inf");
  EXPECT_EQ(csvNumber(0.0 / 0.0), "nan");
  EXPECT_EQ(csvNumber(24.0812345678), "24.0812");
  EXPECT_EQ(csvNumber(24.0812345678, 3), "24.1");
  EXPECT_EQ(fixed(2.0 / 3.0, 2), "0.67");
}

TEST(PaperEvaluation, ListsItsExperimentsInOrder) {
  EXPECT_EQ(experimentNames(),
            (std::vector<std::string>{"value", "tables", "structured", "unstructured", "params",
                                      "query", "performance", "compression", "denoise", "time"}));
}

TEST(PaperEvaluation, UnknownExperimentFailsBeforeWritingAnything) {
  const std::filesystem::path out = std::filesystem::path(MFADVR_TEST_TMP_DIR) / "eval_unknown";
  std::filesystem::remove_all(out);
  EvalOptions o;
  o.out = out;
  o.only = {"tables", "colour"};
  o.vtk = false;
  o.plots = false;
  o.progress = false;
  try {
    runPaperEvaluation(o, "test");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown experiment 'colour'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("value, tables"), std::string::npos);
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(PaperEvaluation, QueryStudyAloneWritesItsCsvAndReport) {
  const std::filesystem::path out = std::filesystem::path(MFADVR_TEST_TMP_DIR) / "eval_query";
  std::filesystem::remove_all(out);
  EvalOptions o;
  o.out = out;
  o.quick = true;
  o.only = {"query"};
  o.vtk = false;
  o.plots = false;
  o.progress = false;
  const EvaluationSummary s = runPaperEvaluation(o, "test");
  EXPECT_TRUE(s.failed.empty());
  EXPECT_TRUE(std::filesystem::is_regular_file(out / "fig12_query_time.csv"));
  EXPECT_TRUE(std::filesystem::is_regular_file(out / "report.md"));
  EXPECT_FALSE(std::filesystem::exists(out / "fig05_value_accuracy.csv"));
  EXPECT_GE(s.matches + s.differences, 2);
}
