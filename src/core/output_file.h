#pragma once
// Outputs are written to a temporary file beside the target and renamed into place only
// when every output of a run succeeded, so a failed run never leaves partial output.
#include <string>
#include <vector>

namespace inim {

class OutputSet {
 public:
  OutputSet() = default;
  ~OutputSet();  // removes temporaries not committed
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // Returns the temporary path to write for `finalPath` (same folder and extension, so
  // format-by-extension writers still work). Creates the folder if needed.
  std::string add(const std::string& finalPath);
  // Renames every temporary into place.
  void commit();

 private:
  struct Entry { std::string tmp, final; };
  std::vector<Entry> entries_;
  bool committed_ = false;
};

// Writes `text` to `path` (a temporary from OutputSet::add, usually); throws if the file cannot
// be written completely.
void writeTextFile(const std::string& path, const std::string& text);

// Folder that holds spectra/, optics/, scenes/: $INIM_DATA_DIR or the source tree.
std::string dataDir();
// `rel` under dataDir(), unless it is absolute or exists relative to the working directory.
std::string dataPath(const std::string& rel);

}  // namespace inim
