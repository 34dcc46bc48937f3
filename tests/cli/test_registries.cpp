// Every registered kind is documented: the tables that dispatch commands, studies, panel
// estimators, field kinds and file kinds are the lists --help prints, and each entry must be
// named where a reader looks for it (README's tour, validation/, docs/view-estimators.md,
// docs/formats.md). Adding a kind without its documentation fails here.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "cli/commands.h"
#include "core/file_kinds.h"
#include "display_view/estimators/panel_estimator.h"
#include "field_files/field_factory.h"
#include "fixtures.h"
#include "studies/studies.h"

using namespace inim;

namespace {

std::string sourceFile(const std::string& relative) {
  const std::string text = fixtures::readBytes(std::string(INIM_SOURCE_DATA_DIR) + "/" + relative);
  EXPECT_FALSE(text.empty()) << relative;
  return text;
}

bool mentions(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

}  // namespace

TEST(Registries, EveryCommandIsInTheReadmeTour) {
  const std::string readme = sourceFile("README.md");
  for (const cli::Command& c : cli::commands())
    EXPECT_TRUE(mentions(readme, std::string("$B ") + c.name) || mentions(readme, std::string("inim ") + c.name))
        << c.name;
}

TEST(Registries, CommandNamesAreUniqueAndSummarised) {
  std::set<std::string> names;
  for (const cli::Command& c : cli::commands()) {
    EXPECT_TRUE(names.insert(c.name).second) << c.name;
    EXPECT_GT(std::string(c.summary).size(), 10u) << c.name;
  }
}

TEST(Registries, EveryStudyHasItsFolderAndIsListed) {
  const std::string index = sourceFile("validation/README.md");
  for (const StudyInfo& s : studies()) {
    EXPECT_TRUE(mentions(index, s.name)) << s.name;
    EXPECT_TRUE(mentions(sourceFile(std::string("validation/") + s.name + "/report.md"), "inim study " + std::string(s.name)))
        << s.name;
  }
}

TEST(Registries, EveryPanelEstimatorIsDocumentedAndNamedInOrder) {
  const std::string doc = sourceFile("docs/view-estimators.md");
  for (size_t i = 0; i < panelEstimators().size(); ++i) {
    const PanelEstimatorInfo& e = panelEstimators()[i];
    EXPECT_EQ(size_t(e.kind), i) << e.name;  // the table is indexed by kind
    EXPECT_TRUE(mentions(doc, "| `" + std::string(e.name) + "` |")) << e.name;
  }
}

TEST(Registries, EveryFieldAndFileKindIsInTheFormatsDoc) {
  const std::string doc = sourceFile("docs/formats.md");
  for (size_t i = 0; i < fieldKinds().size(); ++i) {
    EXPECT_EQ(size_t(fieldKinds()[i].kind), i);
    EXPECT_TRUE(mentions(doc, "| " + std::string(fieldKinds()[i].name) + " |")) << fieldKinds()[i].name;
  }
  for (size_t i = 0; i < fileKinds().size(); ++i) {
    const FileKindInfo& k = fileKinds()[i];
    EXPECT_EQ(size_t(k.kind), i);
    EXPECT_TRUE(mentions(doc, "| " + std::string(k.name) + " |")) << k.name;
    for (const char* e : k.extensions) EXPECT_TRUE(mentions(doc, "`" + std::string(e) + "`")) << e;
  }
}

TEST(Registries, FileKindsAreToldByExtensionWhateverTheCase) {
  EXPECT_EQ(fileKindOf("a/b/EIA.EXR"), FileKind::Exr);
  EXPECT_EQ(fileKindOf("x.TiFf"), FileKind::Tiff);
  EXPECT_EQ(fileKindOf("scene.json"), FileKind::Json);
  EXPECT_FALSE(fileKindOf("notes.md").has_value());
  EXPECT_FALSE(fileKindOf("no_extension").has_value());
  for (const FileKindInfo& k : fileKinds())
    for (const char* e : k.extensions) EXPECT_EQ(fileKindOf(std::string("f") + e), k.kind) << e;
  EXPECT_EQ(fixtures::expectInputError([] { requireFileKind("out.png", "out", {FileKind::Exr}, "an EXR"); }).key(),
            "out");
}
