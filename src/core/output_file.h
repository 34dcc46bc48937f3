#pragma once
// Outputs are written to a temporary file beside the target and renamed into place only
// when every output of a run succeeded, so a failed or interrupted run never leaves partial
// output and the old outputs stay intact. Temporaries are named .<stem>.tmp<pid><ext>; those
// of dead processes (killed, power loss) are removed by the next run into the same folder.
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
  // format-by-extension writers still work). Creates the folder if needed and removes stale
  // temporaries of dead processes there.
  std::string add(const std::string& finalPath);
  // Flushes every temporary to disk, then renames all into place and flushes the folders.
  // Throws Interrupted (core/interrupt.h) instead if a signal came first; a signal during the
  // renames waits for them, so the outputs of one run change together.
  void commit();

 private:
  struct Entry { std::string tmp, final; };
  std::vector<Entry> entries_;
  std::vector<std::string> folders_;  // of the entries: swept once, flushed after the renames
  bool committed_ = false;
};

// `message` with every temporary this process made (OutputSet::add) replaced by the output it
// stands for, so that an error while writing (a full disk) names the file the user asked for.
std::string withOutputNames(std::string message);

// Removes inim's temporaries (.<stem>.tmp<pid><ext>) in `folder` whose process is gone;
// returns how many. Other files, and temporaries of live processes, are left alone.
int removeStaleTemporaries(const std::string& folder);

// Writes `text` to `path` (a temporary from OutputSet::add, usually); throws if the file cannot
// be written completely.
void writeTextFile(const std::string& path, const std::string& text);

// Folder that holds spectra/, optics/, scenes/: $INIM_DATA_DIR or the source tree.
std::string dataDir();
// `rel` under dataDir(), unless it is absolute or exists relative to the working directory.
std::string dataPath(const std::string& rel);

}  // namespace inim
