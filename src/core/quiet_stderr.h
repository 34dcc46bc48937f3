#pragma once
// Silences what image libraries print on their own while an image file is read (or a write
// stopped by Ctrl-C is abandoned). libpng's default error handler, which OpenImageIO's PNG
// reader keeps, prints "libpng error: ..." to stderr before OIIO reports the same error to
// inim, whose one message then says it again.
// While any PNG is being read, stderr goes to /dev/null: the first reader redirects it, the last
// one restores it (reads may run on several threads; what another thread prints meanwhile is
// lost, so only PNG reads are silenced).
//
//   LibraryStderrSilenced quiet(path);  // no effect unless path ends in .png
//   auto in = OIIO::ImageInput::open(path);
#include <string>

namespace inim {

class LibraryStderrSilenced {
 public:
  explicit LibraryStderrSilenced(const std::string& path);
  ~LibraryStderrSilenced();
  LibraryStderrSilenced(const LibraryStderrSilenced&) = delete;
  LibraryStderrSilenced& operator=(const LibraryStderrSilenced&) = delete;

 private:
  bool active_ = false;
};

}  // namespace inim
