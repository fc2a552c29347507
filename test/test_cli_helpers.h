// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Helpers of the comap tests: a scratch directory, running the binary and capturing its output
// and exit code, small files, and the test pair (a bumpy capsule and a bent, remeshed copy with
// ground truth from the construction).

#ifndef SMC_TEST_CLI_HELPERS_H
#define SMC_TEST_CLI_HELPERS_H

#include "test_pairs.h"

#include <CGAL/Surface_mesh_correspondence/map_io.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace smc_cli_test {

using namespace smc_test;

/// A scratch directory, removed at exit.
inline const std::string& scratch()
{
  struct Dir
  {
    std::string path;
    Dir()
    {
      char name[] = "/tmp/smc_test_cli_XXXXXX";
      const char* made = ::mkdtemp(name);
      path = made ? made : "/tmp";
    }
    ~Dir()
    {
      if(path != "/tmp")
      {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
      }
    }
  };
  static const Dir dir;
  return dir.path;
}

inline std::string in_scratch(const std::string& name) { return scratch() + "/" + name; }

inline std::string read_text(const std::string& file)
{
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_text(const std::string& file, const std::string& text) { std::ofstream(file) << text; }

inline std::vector<std::string> lines_of(const std::string& text)
{
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while(std::getline(in, line)) out.push_back(line);
  return out;
}

/// Exit code, stdout and stderr of one run of comap.
struct Run
{
  int code = -1;
  std::string out, err;
  std::vector<std::string> err_lines() const { return lines_of(err); }
};

/// Runs comap with `arguments`; `environment` ("NAME=VALUE ...") is set for this run only.
inline Run comap(const std::string& arguments, const std::string& environment = "")
{
  static int counter = 0;
  const std::string out = in_scratch("stdout" + std::to_string(counter)), err = in_scratch("stderr" + std::to_string(counter));
  ++counter;
  const std::string command = (environment.empty() ? std::string() : "env " + environment + " ") +
                              std::string(SMC_TEST_BINARY_DIR) + "/bin/comap " + arguments + " > " + out + " 2> " + err;
  const int status = std::system(command.c_str());
  Run r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

inline void write_off(const std::string& file, const Mesh& m)
{
  std::ofstream out(file);
  out.precision(17);
  CGAL::IO::write_OFF(out, m);
}

inline void write_map(const std::string& file, const std::vector<std::size_t>& map, int base)
{
  CGAL::Surface_mesh_correspondence::write_vertex_indices(file, map, base);
}

inline std::vector<std::size_t> read_map(const std::string& file, int base)
{
  return CGAL::Surface_mesh_correspondence::read_vertex_indices(file, base);
}

inline std::vector<std::size_t> identity(std::size_t n)
{
  std::vector<std::size_t> v(n);
  for(std::size_t i = 0; i < n; ++i) v[i] = i;
  return v;
}

/// The test pair, written once: A.off (bumpy capsule), B.off (bent by 1 radian and remeshed),
/// gt_12 / gt_21 (0-based), and a perturbed copy of the ground truth.
struct Cli_pair
{
  Shape_pair pair;
  std::vector<std::size_t> noisy_12, noisy_21;
  std::string a, b;
  Cli_pair()
  {
    pair = bent_pair(bumpy_capsule(), 4.0, 1.0, true);
    noisy_12 = perturbed(pair.gt_12, pair.m2, 0.5, 3, 1);
    noisy_21 = perturbed(pair.gt_21, pair.m1, 0.5, 3, 2);
    a = in_scratch("A.off");
    b = in_scratch("B.off");
    write_off(a, pair.m1);
    write_off(b, pair.m2);
  }
};

inline const Cli_pair& cli_pair()
{
  static const Cli_pair p;
  return p;
}

/// Settings that keep the small test runs fast (few eigenpairs, one functional map fit, a short
/// schedule), as a settings file: " --quiet --settings FILE". The settings named in `left_out`
/// keep their defaults.
inline std::string fast_options(const std::vector<std::string>& left_out = {})
{
  const std::vector<std::pair<std::string, std::string> > fast = {
      {"number_of_eigenpairs", "30"},        {"number_of_wks_energies", "30"},
      {"ring_schedule", "[3, 2]"},           {"number_of_candidates", "10"},
      {"trws_number_of_iterations", "30"},   {"zoomout_final_size", "40"},
      {"initialization_fits", "[[20, 0.03, 0.3]]"}, {"fit_selection_basis_size", "30"},
      {"zoomout_number_of_samples", "300"},  {"initialization_number_of_wks_energies", "40"},
      {"signed_descriptor_smoothing", "30"}};
  std::string json, file = "fast";
  for(const auto& s : fast)
  {
    if(std::find(left_out.begin(), left_out.end(), s.first) != left_out.end())
    {
      file += "-" + s.first;
      continue;
    }
    json += std::string(json.empty() ? "{\n" : ",\n") + "  \"" + s.first + "\": " + s.second;
  }
  file = in_scratch(file + ".json");
  write_text(file, json + "\n}\n");
  return " --quiet --settings " + file;
}

// ------------------------------------------------------------------- a minimal PNG writer

inline std::uint32_t crc32(const unsigned char* data, std::size_t n, std::uint32_t crc = 0)
{
  crc = ~crc;
  for(std::size_t i = 0; i < n; ++i)
  {
    crc ^= data[i];
    for(int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

/// Writes an 8-bit RGB PNG (one stored, uncompressed deflate block): rows top to bottom.
inline void write_png(const std::string& file, int width, int height, const std::vector<unsigned char>& rgb)
{
  std::vector<unsigned char> raw;
  for(int y = 0; y < height; ++y)
  {
    raw.push_back(0);  // filter: none
    raw.insert(raw.end(), rgb.begin() + y * width * 3, rgb.begin() + (y + 1) * width * 3);
  }
  std::vector<unsigned char> z = {0x78, 0x01, 0x01};
  const std::uint16_t len = static_cast<std::uint16_t>(raw.size()), nlen = static_cast<std::uint16_t>(~len);
  z.push_back(len & 0xff);
  z.push_back(len >> 8);
  z.push_back(nlen & 0xff);
  z.push_back(nlen >> 8);
  z.insert(z.end(), raw.begin(), raw.end());
  std::uint32_t s1 = 1, s2 = 0;
  for(unsigned char c : raw)
  {
    s1 = (s1 + c) % 65521;
    s2 = (s2 + s1) % 65521;
  }
  const std::uint32_t adler = (s2 << 16) | s1;
  for(int k = 3; k >= 0; --k) z.push_back((adler >> (8 * k)) & 0xff);
  std::ofstream out(file, std::ios::binary);
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  out.write(reinterpret_cast<const char*>(signature), 8);
  auto chunk = [&](const char* type, const std::vector<unsigned char>& data) {
    std::vector<unsigned char> body(type, type + 4);
    body.insert(body.end(), data.begin(), data.end());
    const std::uint32_t n = static_cast<std::uint32_t>(data.size()), crc = crc32(body.data(), body.size());
    const unsigned char header[4] = {static_cast<unsigned char>(n >> 24), static_cast<unsigned char>(n >> 16),
                                     static_cast<unsigned char>(n >> 8), static_cast<unsigned char>(n)};
    out.write(reinterpret_cast<const char*>(header), 4);
    out.write(reinterpret_cast<const char*>(body.data()), static_cast<std::streamsize>(body.size()));
    const unsigned char c[4] = {static_cast<unsigned char>(crc >> 24), static_cast<unsigned char>(crc >> 16),
                                static_cast<unsigned char>(crc >> 8), static_cast<unsigned char>(crc)};
    out.write(reinterpret_cast<const char*>(c), 4);
  };
  std::vector<unsigned char> ihdr;
  for(std::uint32_t v : {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height)})
    for(int k = 3; k >= 0; --k) ihdr.push_back((v >> (8 * k)) & 0xff);
  for(unsigned char c : {8, 2, 0, 0, 0}) ihdr.push_back(c);
  chunk("IHDR", ihdr);
  chunk("IDAT", z);
  chunk("IEND", {});
}

/// Vertex colours of an ASCII PLY written by comap transfer (r, g, b per vertex).
inline std::vector<std::array<int, 3> > read_ply_colors(const std::string& file)
{
  std::ifstream in(file);
  std::string line;
  std::size_t n = 0;
  while(std::getline(in, line) && line != "end_header")
    if(line.rfind("element vertex ", 0) == 0) n = std::stoul(line.substr(15));
  std::vector<std::array<int, 3> > colors(n);
  for(std::size_t i = 0; i < n; ++i)
  {
    double x, y, z;
    in >> x >> y >> z >> colors[i][0] >> colors[i][1] >> colors[i][2];
  }
  return colors;
}

} // namespace smc_cli_test

#endif // SMC_TEST_CLI_HELPERS_H
