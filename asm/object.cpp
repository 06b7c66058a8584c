// The object and library file formats (docs/object-format.md): writing, strict reading and the
// --dump-object text view. All integers are little-endian. The reader checks, in this order,
// length, magic, version, declared size, CRC-32, then every field and index, and stops at the
// first problem with a message that says what it found.
#include "tmcl/asm/object.hpp"

#include <algorithm>

#include "internal.hpp"
#include <array>
#include <cstdio>
#include <cstring>
#include <set>


namespace tmcl {
namespace {

using detail::upper;

constexpr std::uint8_t kObjMagic[8] = {'T', 'M', 'C', 'L', 'O', 'B', 'J', 0};
constexpr std::uint8_t kLibMagic[8] = {'T', 'M', 'C', 'L', 'L', 'I', 'B', 0};
constexpr std::size_t kHeader = 16;  // magic, version, flags, size
constexpr std::size_t kTrailer = 4;  // CRC-32

class Writer {
 public:
  void u8(std::uint8_t v) { out.push_back(v); }
  void u16(std::uint16_t v) {
    for (int i = 0; i < 2; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void i64(std::int64_t v) {
    auto u = static_cast<std::uint64_t>(v);
    for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(u >> (8 * i)));
  }
  void str(const std::string& s) {
    u16(static_cast<std::uint16_t>(std::min<std::size_t>(s.size(), 0xFFFF)));
    out.insert(out.end(), s.begin(), s.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(s.size(), 0xFFFF)));
  }
  void bytes(const std::vector<std::uint8_t>& b) { out.insert(out.end(), b.begin(), b.end()); }
  // Fills in the size field and appends the CRC.
  std::vector<std::uint8_t> finish() {
    auto size = static_cast<std::uint32_t>(out.size() + kTrailer);
    for (int i = 0; i < 4; ++i) out[12 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(size >> (8 * i));
    u32(crc32(out.data(), out.size()));
    return std::move(out);
  }
  std::vector<std::uint8_t> out;
};

// A bounds-checked cursor: every read checks what is left and fails instead of reading past it.
class Reader {
 public:
  Reader(const std::uint8_t* p, std::size_t n) : p_(p), n_(n) {}
  bool u8(std::uint8_t& v) {
    if (!need(1)) return false;
    v = p_[pos_++];
    return true;
  }
  bool u16(std::uint16_t& v) {
    if (!need(2)) return false;
    v = static_cast<std::uint16_t>(p_[pos_] | (p_[pos_ + 1] << 8));
    pos_ += 2;
    return true;
  }
  bool u32(std::uint32_t& v) {
    if (!need(4)) return false;
    v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | p_[pos_ + static_cast<std::size_t>(i)];
    pos_ += 4;
    return true;
  }
  bool i64(std::int64_t& v) {
    if (!need(8)) return false;
    std::uint64_t u = 0;
    for (int i = 7; i >= 0; --i) u = (u << 8) | p_[pos_ + static_cast<std::size_t>(i)];
    pos_ += 8;
    v = static_cast<std::int64_t>(u);
    return true;
  }
  bool str(std::string& s) {
    std::uint16_t len = 0;
    if (!u16(len) || !need(len)) return false;
    s.assign(reinterpret_cast<const char*>(p_ + pos_), len);
    pos_ += len;
    return true;
  }
  bool skip(std::size_t k) {
    if (!need(k)) return false;
    pos_ += k;
    return true;
  }
  // A count of records of at least `min_size` bytes each must fit in what is left.
  bool count(std::uint32_t& n, std::size_t min_size) {
    return u32(n) && static_cast<std::uint64_t>(n) * min_size <= n_ - pos_;
  }
  std::size_t pos() const { return pos_; }
  std::size_t left() const { return n_ - pos_; }
  const std::uint8_t* here() const { return p_ + pos_; }

 private:
  bool need(std::size_t k) const { return k <= n_ - pos_; }
  const std::uint8_t* p_;
  std::size_t n_;
  std::size_t pos_ = 0;
};

std::uint32_t get32(const std::uint8_t* p) {
  return std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24);
}


bool printable(const std::string& s) {
  for (unsigned char c : s)
    if (c < 0x20 || c == 0x7f) return false;
  return true;
}


// Checks what every object and library starts with: length, magic, version, size, CRC.
bool check_envelope(const std::uint8_t* data, std::size_t size, const std::uint8_t (&magic)[8], const char* what,
                    std::string& error) {
  if (size < 8 || std::memcmp(data, magic, 8) != 0) {
    error = std::string("not a tmcl ") + what + " (wrong magic bytes)";
    return false;
  }
  if (size < kHeader + kTrailer) {
    error = "truncated: " + std::to_string(size) + " bytes, shorter than the " + std::to_string(kHeader + kTrailer) +
            "-byte header and checksum";
    return false;
  }
  auto version = static_cast<std::uint16_t>(data[8] | (data[9] << 8));
  if (version != kObjectVersion) {
    error = std::string(what) + " format version " + std::to_string(version) + "; this tmclasm reads version " +
            std::to_string(kObjectVersion) + " (rebuild it with this tmclasm)";
    return false;
  }
  std::uint32_t declared = get32(data + 12);
  if (declared != size) {
    error = declared > size ? "truncated: the header says " + std::to_string(declared) + " bytes, the file has " +
                                  std::to_string(size)
                            : "the header says " + std::to_string(declared) + " bytes, the file has " +
                                  std::to_string(size) + " (extra bytes at the end)";
    return false;
  }
  std::uint32_t stored = get32(data + size - 4), actual = crc32(data, size - 4);
  if (stored != actual) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "corrupted: CRC-32 is 0x%08X, the file says 0x%08X", actual, stored);
    error = buf;
    return false;
  }
  return true;
}

}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t size) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < size; ++i) c = table[(c ^ data[i]) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

FileKind sniff_file(const std::string& bytes) {
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kObjMagic, 8) == 0) return FileKind::Object;
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kLibMagic, 8) == 0) return FileKind::Library;
  return FileKind::Source;
}

std::vector<std::uint8_t> write_object(const ObjectFile& obj) {
  Writer w;
  w.out.insert(w.out.end(), kObjMagic, kObjMagic + 8);
  w.u16(kObjectVersion);
  w.u16(obj.flags);
  w.u32(0);  // size, filled in by finish()
  w.str(obj.target);
  w.u32(static_cast<std::uint32_t>(obj.files.size()));
  for (const auto& f : obj.files) w.str(f);
  w.u32(static_cast<std::uint32_t>(obj.code.size()));
  for (std::size_t i = 0; i < obj.code.size(); ++i) {
    const Instruction& ins = obj.code[i];
    w.u8(ins.op);
    w.u8(ins.type);
    w.u8(ins.motor);
    w.u8(i < obj.code_flags.size() ? obj.code_flags[i] : 0);
    w.u32(static_cast<std::uint32_t>(ins.value));
    ObjLine l = i < obj.lines.size() ? obj.lines[i] : ObjLine{};
    w.u32(l.file);
    w.u32(l.line);
  }
  w.u32(static_cast<std::uint32_t>(obj.symbols.size()));
  for (const auto& s : obj.symbols) {
    w.str(s.name);
    w.u8(static_cast<std::uint8_t>(s.kind));
    w.u8(static_cast<std::uint8_t>(s.binding));
    w.u8(static_cast<std::uint8_t>(s.term));
    w.u8(0);
    w.i64(s.value);
    w.u32(s.term_symbol);
    w.u32(s.file);
    w.u32(s.line);
  }
  w.u32(static_cast<std::uint32_t>(obj.relocs.size()));
  for (const auto& r : obj.relocs) {
    w.u32(r.index);
    w.u8(static_cast<std::uint8_t>(r.field));
    w.u8(static_cast<std::uint8_t>(r.term));
    w.u16(0);
    w.u32(r.symbol);
    w.i64(r.addend);
  }
  return w.finish();
}

bool read_object(const std::uint8_t* data, std::size_t size, ObjectFile& out, std::string& error) {
  if (!check_envelope(data, size, kObjMagic, "object", error)) return false;
  out = ObjectFile{};
  out.flags = static_cast<std::uint16_t>(data[10] | (data[11] << 8));
  if (out.flags & ~kObjNoAppendStop) {
    error = "unknown flags 0x" + std::to_string(out.flags) + " in the header (written by a newer tmclasm?)";
    return false;
  }
  Reader r(data + kHeader, size - kHeader - kTrailer);
  auto bad = [&](const std::string& what) {
    error = "malformed at byte " + std::to_string(kHeader + r.pos()) + ": " + what;
    return false;
  };
  if (!r.str(out.target)) return bad("the target name runs past the end");
  // Whether the target is a known module is the linker's question, not the reader's.
  if (out.target.empty() || !printable(out.target)) return bad("invalid target name");

  std::uint32_t n = 0;
  if (!r.count(n, 2)) return bad("the file table runs past the end");
  out.files.resize(n);
  for (auto& f : out.files)
    if (!r.str(f)) return bad("a file name runs past the end");
    else if (f.empty() || !printable(f)) return bad("invalid file name in the file table");

  auto file_ok = [&](std::uint32_t f) { return f == kNoIndex || f < out.files.size(); };
  if (!r.count(n, 16)) return bad("the instruction table runs past the end");
  out.code.resize(n);
  out.code_flags.resize(n);
  out.lines.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    Instruction& ins = out.code[i];
    std::uint32_t value = 0;
    if (!r.u8(ins.op) || !r.u8(ins.type) || !r.u8(ins.motor) || !r.u8(out.code_flags[i]) || !r.u32(value) ||
        !r.u32(out.lines[i].file) || !r.u32(out.lines[i].line))
      return bad("instruction " + std::to_string(i) + " runs past the end");
    ins.value = static_cast<std::int32_t>(value);
    if (out.code_flags[i] & ~kInsRaw) return bad("instruction " + std::to_string(i) + " has unknown flags");
    if (!file_ok(out.lines[i].file)) return bad("instruction " + std::to_string(i) + " names file " +
                                                std::to_string(out.lines[i].file) + ", which is not in the file table");
  }

  if (!r.count(n, 24)) return bad("the symbol table runs past the end");
  out.symbols.resize(n);
  std::set<std::string> names;
  for (std::uint32_t i = 0; i < n; ++i) {
    ObjSymbol& s = out.symbols[i];
    std::uint8_t kind = 0, binding = 0, term = 0, pad = 0;
    if (!r.str(s.name) || !r.u8(kind) || !r.u8(binding) || !r.u8(term) || !r.u8(pad) || !r.i64(s.value) ||
        !r.u32(s.term_symbol) || !r.u32(s.file) || !r.u32(s.line))
      return bad("symbol " + std::to_string(i) + " runs past the end");
    std::string which = "symbol " + std::to_string(i);
    if (!is_valid_name(s.name)) return bad(which + " has an invalid name");
    which += " '" + s.name + "'";
    if (kind > 1 || binding > 2 || term > 2 || pad != 0) return bad(which + " has an invalid kind, binding or term");
    s.kind = static_cast<ObjSymKind>(kind);
    s.binding = static_cast<ObjBinding>(binding);
    s.term = static_cast<ObjTerm>(term);
    if (!names.insert(upper(s.name)).second) return bad(which + " is defined twice");
    if (!file_ok(s.file)) return bad(which + " names a file that is not in the file table");
    if (s.binding == ObjBinding::Import &&
        (s.kind != ObjSymKind::Label || s.term != ObjTerm::Absolute || s.value != 0 || s.term_symbol != kNoIndex))
      return bad(which + " is an import with a value");
    if (s.kind == ObjSymKind::Label &&
        s.binding != ObjBinding::Import &&
        (s.term != ObjTerm::Base || s.value < 0 || s.value > static_cast<std::int64_t>(out.code.size())))
      return bad(which + " is a label outside the object");
    if ((s.term == ObjTerm::Symbol) != (s.term_symbol != kNoIndex))
      return bad(which + " has an inconsistent term");
  }
  for (const auto& s : out.symbols)
    if (s.term == ObjTerm::Symbol &&
        (s.term_symbol >= out.symbols.size() || out.symbols[s.term_symbol].binding != ObjBinding::Import))
      return bad("symbol '" + s.name + "' refers to a symbol that is not an import");

  if (!r.count(n, 20)) return bad("the relocation table runs past the end");
  out.relocs.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    ObjReloc& x = out.relocs[i];
    std::uint8_t field = 0, term = 0;
    std::uint16_t pad = 0;
    if (!r.u32(x.index) || !r.u8(field) || !r.u8(term) || !r.u16(pad) || !r.u32(x.symbol) || !r.i64(x.addend))
      return bad("relocation " + std::to_string(i) + " runs past the end");
    std::string which = "relocation " + std::to_string(i);
    if (field > 2 || term < 1 || term > 2 || pad != 0) return bad(which + " has an invalid field or kind");
    x.field = static_cast<Field>(field);
    x.term = static_cast<ObjTerm>(term);
    if (x.index >= out.code.size()) return bad(which + " refers to an instruction outside the object");
    if (x.term == ObjTerm::Base ? x.symbol != kNoIndex
                                : (x.symbol >= out.symbols.size() || out.symbols[x.symbol].binding != ObjBinding::Import))
      return bad(which + " refers to a symbol that is not an import");
    if (i > 0 && std::make_pair(out.relocs[i - 1].index, static_cast<int>(out.relocs[i - 1].field)) >=
                     std::make_pair(x.index, static_cast<int>(x.field)))
      return bad(which + " is out of order or duplicated");
    if (field_of(out.code[x.index], x.field) != 0)
      return bad(which + ": the relocated field of instruction " + std::to_string(x.index) + " is not 0");
  }
  if (r.left() != 0) return bad(std::to_string(r.left()) + " unexpected bytes after the relocation table");
  return true;
}

std::vector<std::uint8_t> write_library(const Library& lib) {
  Writer w;
  w.out.insert(w.out.end(), kLibMagic, kLibMagic + 8);
  w.u16(kObjectVersion);
  w.u16(0);
  w.u32(0);
  w.u32(static_cast<std::uint32_t>(lib.members.size()));
  for (const auto& m : lib.members) {
    w.str(m.name);
    auto bytes = write_object(m.object);
    w.u32(static_cast<std::uint32_t>(bytes.size()));
    w.bytes(bytes);
  }
  return w.finish();
}

bool read_library(const std::uint8_t* data, std::size_t size, Library& out, std::string& error) {
  if (!check_envelope(data, size, kLibMagic, "library", error)) return false;
  out = Library{};
  if (data[10] != 0 || data[11] != 0) {
    error = "unknown flags in the header (written by a newer tmclasm?)";
    return false;
  }
  Reader r(data + kHeader, size - kHeader - kTrailer);
  std::uint32_t n = 0;
  if (!r.count(n, 6)) {
    error = "malformed: the member count runs past the end";
    return false;
  }
  std::set<std::string> names;
  for (std::uint32_t i = 0; i < n; ++i) {
    LibraryMember m;
    std::uint32_t len = 0;
    if (!r.str(m.name) || !r.u32(len) || len > r.left()) {
      error = "malformed: member " + std::to_string(i + 1) + " runs past the end";
      return false;
    }
    if (m.name.empty() || !printable(m.name) || !names.insert(m.name).second) {
      error = "malformed: member " + std::to_string(i + 1) + " has an empty, unprintable or repeated name";
      return false;
    }
    std::string why;
    if (!read_object(r.here(), len, m.object, why)) {
      error = "member " + std::to_string(i + 1) + " '" + m.name + "': " + why;
      return false;
    }
    r.skip(len);
    out.members.push_back(std::move(m));
  }
  if (r.left() != 0) {
    error = "malformed: " + std::to_string(r.left()) + " unexpected bytes after the last member";
    return false;
  }
  return true;
}

}  // namespace tmcl
