#pragma once
// Every kind of file inim reads or writes, told by its extension (case-insensitive), in one
// table: the only place an extension is matched. Stages choose their loader or writer by the
// kind (field_files/field_factory.h keeps the table of field loaders), so `--help`, messages
// and docs/formats.md read the same list.
//
//   if (fileKindOf(path) == FileKind::Png) ...                     // an encoded image
//   requireFileKind(out, "out", {FileKind::Exr}, "an OpenEXR file name (.exr)");
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace inim {

// One kind per extension family; what a kind holds depends on where it is read (a .json is
// a scene, a display or a run file by the key that names it).
enum class FileKind { Json, Inimrf, Ply, Splat, Exr, Png, Hdr, Tiff, Pfm, Npy, Txt, Irays, Sdf, Dat, Cube, Clf, Zmx, Agf };

struct FileKindInfo {
  FileKind kind;
  const char* name;                     // "OpenEXR image"
  std::vector<const char*> extensions;  // lower case, with the dot
  const char* description;              // one line: what inim keeps in such a file
};

// The table, in the order of FileKind.
const std::vector<FileKindInfo>& fileKinds();
const FileKindInfo& fileKindInfo(FileKind k);

// The kind of `path` by its extension; none for an extension inim does not know.
std::optional<FileKind> fileKindOf(const std::string& path);
inline bool isFileKind(const std::string& path, FileKind k) { return fileKindOf(path) == k; }

// The kind of `path` when it is one of `kinds`; else InputError(file, key, "\"path\"", expected).
FileKind requireFileKind(const std::string& path, const std::string& key, std::initializer_list<FileKind> kinds,
                         const std::string& expected, const std::string& file = "");

}  // namespace inim
