#pragma once
// Text files from Windows optical software (Zemax .zmx lens files and .agf glass catalogues)
// come as UTF-16 (little or big endian, with or without a byte-order mark) or as UTF-8/ASCII,
// with CRLF or LF line ends. Readers take the bytes through here and parse plain UTF-8.
#include <string>

namespace inim {

// The bytes as UTF-8: UTF-16 is recognised by its byte-order mark, or, without one, by NULs in
// every other byte of the first characters; a UTF-8 byte-order mark is dropped; valid UTF-8
// (ASCII included) is returned as it is, anything else read as Latin-1 (a vendor's "Ø" in a
// Windows-1252 file). InputError naming `file` for UTF-16 with an odd number of bytes.
std::string utf8FromBytes(const std::string& bytes, const std::string& file);

// UTF-8 text as UTF-16 little endian with its byte-order mark, as OpticStudio writes its files.
// Invalid UTF-8 bytes are read as Latin-1.
std::string utf16leWithBom(const std::string& utf8);

}  // namespace inim
