// Relocatable objects and libraries (docs/object-format.md): what `tmclasm -c` writes and the
// linker reads. An object is one assembled unit whose addresses start at 0: its instructions, a
// symbol table, relocations for every operand that depends on the unit's final place or on a
// name imported from another unit, the source file and line of every instruction, and the target
// it was checked against. A library is a set of objects in one file.
//
// Reading never trusts the bytes: every read is bounds-checked, every index validated, and the
// CRC-32 checked, so a truncated, corrupted or foreign file yields an error message, never a
// crash or an object that does not mean what its writer meant.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tmcl/isa.hpp"

namespace tmcl {

inline constexpr std::uint16_t kObjectVersion = 1;
inline constexpr std::uint32_t kNoIndex = 0xFFFFFFFFu;

enum class ObjSymKind : std::uint8_t { Label = 0, Constant = 1 };
enum class ObjBinding : std::uint8_t { Local = 0, Export = 1, Import = 2 };
// What a symbol's value or a relocation's addend is added to.
enum class ObjTerm : std::uint8_t {
  Absolute = 0,  // nothing: the value is final
  Base = 1,      // the address of the object's first instruction
  Symbol = 2,    // the value of an imported symbol
};

struct ObjSymbol {
  std::string name;  // as spelt at its definition (or #import)
  ObjSymKind kind = ObjSymKind::Label;
  ObjBinding binding = ObjBinding::Local;
  ObjTerm term = ObjTerm::Absolute;  // imports: Absolute, value 0
  std::int64_t value = 0;            // labels: address within the object (term Base)
  std::uint32_t term_symbol = kNoIndex;  // term Symbol: index of an import in `symbols`
  std::uint32_t file = kNoIndex;     // where defined (imports: where imported); index into `files`
  std::uint32_t line = 0;
};

struct ObjReloc {
  std::uint32_t index = 0;  // instruction
  Field field = Field::Value;
  ObjTerm term = ObjTerm::Base;  // Base or Symbol
  std::uint32_t symbol = kNoIndex;  // term Symbol: index of an import in `symbols`
  std::int64_t addend = 0;          // the field becomes addend + base or addend + symbol
};

// Per-instruction flags.
inline constexpr std::uint8_t kInsRaw = 1;  // written with .raw: no operand checks at link time

struct ObjLine {
  std::uint32_t file = kNoIndex;  // index into `files`
  std::uint32_t line = 0;
};

// Object-wide flags.
inline constexpr std::uint16_t kObjNoAppendStop = 1;  // the source said #no_append_stop

struct ObjectFile {
  std::string target = "generic";     // the -t it was assembled with
  std::uint16_t flags = 0;
  std::vector<std::string> files;     // source files, as named in messages
  std::vector<Instruction> code;      // relocated fields hold 0; the addend is in the relocation
  std::vector<std::uint8_t> code_flags;  // kInsRaw...
  std::vector<ObjLine> lines;         // one per instruction
  std::vector<ObjSymbol> symbols;     // locals, exports and imports, in definition order
  std::vector<ObjReloc> relocs;       // sorted by instruction, then field
  friend bool operator==(const ObjectFile&, const ObjectFile&) = default;
};

struct LibraryMember {
  std::string name;  // e.g. "homing.o"
  ObjectFile object;
  friend bool operator==(const LibraryMember&, const LibraryMember&) = default;
};

struct Library {
  std::vector<LibraryMember> members;  // in the order they were added; the linker scans them so
};

enum class FileKind { Source, Object, Library };
// Tells an object or library from source text by its magic bytes.
FileKind sniff_file(const std::string& bytes);

std::vector<std::uint8_t> write_object(const ObjectFile& obj);
// Reads an object; false with `error` saying what is wrong (without the file name).
bool read_object(const std::uint8_t* data, std::size_t size, ObjectFile& out, std::string& error);
std::vector<std::uint8_t> write_library(const Library& lib);
bool read_library(const std::uint8_t* data, std::size_t size, Library& out, std::string& error);

// A readable view of every field (tmclasm --dump-object), stable for golden tests; in
// object_dump.cpp, above the disassembler it uses (declared here for the tools that read objects).
std::string dump_object(const ObjectFile& obj);
std::string dump_library(const Library& lib);

// CRC-32 as in zlib, PNG and Ethernet (polynomial 0xEDB88320, reflected, inverted).
std::uint32_t crc32(const std::uint8_t* data, std::size_t size);

}  // namespace tmcl
