// The one codec (vm/isa/include/tmcl/codec.hpp): values MSB first, fields, the 7 instruction
// bytes, checksums and the 9-byte request and reply frames, pinned against byte strings from
// the USB-2-SD manual (section 3.6.1 ROR 0, 350: 01 01 00 00 00 00 01 5E 61) and round trips.
#include <cstdint>

#include "check.hpp"
#include "tmcl/codec.hpp"

using tmcl::Field;
using tmcl::Instruction;

TEST(codec_values_msb_first) {
  std::uint8_t b[4];
  tmcl::encode_be32(0x12345678, b);
  CHECK_EQ(b[0], 0x12);
  CHECK_EQ(b[3], 0x78);
  CHECK_EQ(tmcl::decode_be32(b), 0x12345678);
  for (std::int32_t v : {0, 1, -1, 350, INT32_MIN, INT32_MAX, -123456}) {
    tmcl::encode_be32(v, b);
    CHECK_EQ(tmcl::decode_be32(b), v);
  }
  tmcl::encode_be32(-2, b);
  CHECK_EQ(b[0], 0xFF);
  CHECK_EQ(b[3], 0xFE);
}

TEST(codec_fields) {
  Instruction ins{4, 0, 0, 0};
  tmcl::set_field(ins, Field::Type, 1);
  tmcl::set_field(ins, Field::Motor, 258);  // the low 8 bits
  tmcl::set_field(ins, Field::Value, 4294967295LL);
  CHECK_EQ(ins.type, 1);
  CHECK_EQ(ins.motor, 2);
  CHECK_EQ(ins.value, -1);
  CHECK_EQ(tmcl::field_of(ins, Field::Value), 0xFFFFFFFFu);
  CHECK_EQ(tmcl::field_of(ins, Field::Motor), 2u);
  CHECK(std::string(tmcl::field_name(Field::Motor)) == "motor/bank");
}

TEST(codec_instruction_bytes_and_record_checksum) {
  const Instruction ror{1, 0, 0, 350};
  const auto b = tmcl::encode7(ror);
  const std::uint8_t want[7] = {0x01, 0x00, 0x00, 0x00, 0x00, 0x01, 0x5E};
  for (int i = 0; i < 7; ++i) CHECK_EQ(b[static_cast<std::size_t>(i)], want[i]);
  CHECK(tmcl::decode7(b.data()) == ror);
  CHECK_EQ(tmcl::record_checksum(ror), 0x60);  // .bin: the sum of the 7 bytes
  const Instruction neg{5, 4, 2, -7};
  CHECK(tmcl::decode7(tmcl::encode7(neg).data()) == neg);
}

TEST(codec_request_frame) {
  const tmcl::Frame f = tmcl::encode_request(1, Instruction{1, 0, 0, 350});
  const std::uint8_t want[9] = {0x01, 0x01, 0x00, 0x00, 0x00, 0x00, 0x01, 0x5E, 0x61};
  for (int i = 0; i < 9; ++i) CHECK_EQ(f[static_cast<std::size_t>(i)], want[i]);
  CHECK(tmcl::frame_checksum_ok(f.data()));
  const tmcl::Request q = tmcl::decode_request(f.data());
  CHECK_EQ(q.address, 1);
  CHECK(q.ins == (Instruction{1, 0, 0, 350}));
  CHECK(q.checksum_ok);
  tmcl::Frame bad = f;
  bad[8] ^= 1;
  CHECK(!tmcl::decode_request(bad.data()).checksum_ok);
  CHECK(!tmcl::frame_checksum_ok(bad.data()));
}

TEST(codec_reply_frame) {
  const tmcl::Frame f = tmcl::encode_reply(tmcl::Reply{2, 1, 100, 6, -5});
  CHECK_EQ(f[0], 2);
  CHECK_EQ(f[1], 1);
  CHECK_EQ(f[2], 100);
  CHECK_EQ(f[3], 6);
  CHECK_EQ(f[4], 0xFF);
  CHECK_EQ(f[7], 0xFB);
  CHECK_EQ(f[8], tmcl::sum8(f.data(), 8));
  const tmcl::Reply r = tmcl::decode_reply(f.data());
  CHECK_EQ(r.host, 2);
  CHECK_EQ(r.module, 1);
  CHECK_EQ(r.status, 100);
  CHECK_EQ(r.op, 6);
  CHECK_EQ(r.value, -5);
  CHECK(r.checksum_ok);
  tmcl::Frame bad = f;
  bad[5] ^= 0x10;
  CHECK(!tmcl::decode_reply(bad.data()).checksum_ok);
}
