// SHA-256 of bench/support against the FIPS 180-4 example digests and digests computed
// by an independent implementation (Python hashlib) at the padding boundaries, then the
// shared workload files against data/SHA256SUMS.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/sha256.hpp"
#include "support/workloads.hpp"

namespace proxima::bench {
namespace test_sha256 {

TEST(Sha256, FipsExamples) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(
      sha256_hex("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnopjklmnopqklmnopqrlmnopqrsm"
                 "nopqrstnopqrstu"),
      "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

std::string pattern(std::size_t n) {
  std::string s(n, '\0');
  for (std::size_t i = 0; i < n; ++i) s[i] = static_cast<char>((i * 7 + 3) % 256);
  return s;
}

TEST(Sha256, PaddingBoundaries) {
  // Lengths around the 55/56-byte padding split and the 64-byte block size.
  const std::pair<std::size_t, const char*> cases[] = {
      {55, "e7313d333c272e639f790978283f9eb392e843d0f29b7016828bb1daa4aac70b"},
      {56, "4324d65f3c103567f5589c710bc08f8523f929a9272e3af36fc968e52abc6c27"},
      {57, "35df609437dcfea3279283ab79fd554e2bf78f8f7ae2de532d8ee300b09e8f73"},
      {63, "81c80242132f230c3bd41b3e63bbcff16107339549214a99614ff26664625055"},
      {64, "39e3d7b6b5d075d37d053ad89b24b41bef4f3c29760c84447cab3f3be1882241"},
      {65, "aacca6ff74fdbb296d165a45cecfa04e5127bc008770fbbdd48006f2d2fae95e"},
      {119, "9ce7368e4daf32341631b492e80359dc9f594b48453cd0dd5bf0b19279cc177e"},
      {120, "7836b787757e95e58b3ca5aec90b1b004e8deba1e50e9675af9cabf1a13a04b5"},
      {128, "d2742f1f4ac6bb7ca2b239ee18402ba8b3f9f8e652d2a72973c2b9ba11c08cf6"},
  };
  for (const auto& [n, digest] : cases) EXPECT_EQ(sha256_hex(pattern(n)), digest) << n << " bytes";
}

TEST(Sha256, IncrementalEqualsOneShot) {
  const std::string data = pattern(1000);
  const std::string expected = sha256_hex(data);
  for (std::size_t chunk : {1u, 3u, 55u, 63u, 64u, 65u, 200u}) {
    Sha256 hasher;
    for (std::size_t i = 0; i < data.size(); i += chunk) hasher.update(std::string_view(data).substr(i, chunk));
    EXPECT_EQ(Sha256::to_hex(hasher.finish()), expected) << "chunk " << chunk;
  }
}

TEST(Sha256, FileDigestAndMissingFile) {
  const auto dir = std::filesystem::temp_directory_path() / "proxima_sha256_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "abc.txt").string();
  std::ofstream(path, std::ios::binary) << "abc";
  const auto digest = sha256_file(path);
  ASSERT_TRUE(digest.ok());
  EXPECT_EQ(*digest, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  const auto missing = sha256_file((dir / "missing.txt").string());
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().what().find("missing.txt"), std::string::npos);
}

TEST(Sha256, VerifyChecksumsReportsMismatchAndMissing) {
  const auto dir = std::filesystem::temp_directory_path() / "proxima_sha256_verify";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream((dir / "a.txt").string(), std::ios::binary) << "abc";
  std::ofstream((dir / "b.txt").string(), std::ios::binary) << "abd";
  std::ofstream((dir / "SHA256SUMS").string(), std::ios::binary)
      << "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad  a.txt\n"
      << "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad  b.txt\n"
      << "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad  c.txt\n";
  const auto report = verify_checksums(dir.string());
  ASSERT_TRUE(report.ok()) << report.error().what();
  EXPECT_EQ(report->matched, std::vector<std::string>{"a.txt"});
  EXPECT_EQ(report->mismatched, std::vector<std::string>{"b.txt"});
  EXPECT_EQ(report->missing, std::vector<std::string>{"c.txt"});
  EXPECT_FALSE(report->ok());

  std::ofstream((dir / "SHA256SUMS").string(), std::ios::binary) << "not-a-digest  a.txt\n";
  const auto bad = verify_checksums(dir.string());
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().what().find("SHA256SUMS:1"), std::string::npos) << bad.error().what();
}

TEST(Sha256, SharedWorkloadsMatchSha256Sums) {
  const std::string dir = workload_dir();
  if (!std::filesystem::exists(workload_path(dir, "SHA256SUMS"))) GTEST_SKIP() << "no workloads in " << dir;
  const auto report = verify_checksums(dir);
  ASSERT_TRUE(report.ok()) << report.error().what();
  EXPECT_TRUE(report->ok());
  EXPECT_EQ(report->matched.size(), 17u);
  EXPECT_TRUE(report->mismatched.empty());
  EXPECT_TRUE(report->missing.empty());
  // One digest spelled out, independent of the list.
  const auto knot = sha256_file(workload_path(dir, "mesh_torusknot.obj"));
  ASSERT_TRUE(knot.ok());
  EXPECT_EQ(*knot, "a7838cbc509c6055ac66205e112c5d7246a9d79536a6b4c8c291f61a0cacba06");
}

}  // namespace test_sha256
}  // namespace proxima::bench
