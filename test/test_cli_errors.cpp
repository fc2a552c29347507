// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap on bad input: a non-zero exit code and one line on stderr that names the problem, never
// a crash.

#include "test_cli_helpers.h"

#include <boost/test/unit_test.hpp>

#include <filesystem>

using namespace smc_cli_test;

namespace {

/// Runs comap and checks: exit code `code`, exactly one line on stderr, starting with "comap:"
/// and containing every piece of `expected`.
void expect_failure(const std::string& arguments, int code, const std::vector<std::string>& expected)
{
  const Run r = comap(arguments);
  BOOST_TEST_CONTEXT("comap " << arguments << "\nstderr: " << r.err)
  {
    BOOST_TEST(r.code == code);
    const std::vector<std::string> lines = r.err_lines();
    BOOST_TEST_REQUIRE(lines.size() == 1u);
    BOOST_TEST(lines[0].rfind("comap:", 0) == 0u);
    for(const std::string& e : expected) BOOST_TEST(lines[0].find(e) != std::string::npos, "missing: " << e);
  }
}

std::string match_args(const std::string& a, const std::string& b, const std::string& extra = "")
{
  return "match " + a + " " + b + " --out-12 " + in_scratch("o12.map") + " --out-21 " + in_scratch("o21.map") +
         " --quiet" + extra;
}

/// The 4 vertices of a tetrahedron shifted by `dx`, as OFF lines.
std::string tetrahedron(double dx)
{
  std::string s;
  for(const char* p : {"0 0 0", "1 0 0", "0 1 0", "0 0 1"})
  {
    std::istringstream in(p);
    double x, y, z;
    in >> x >> y >> z;
    s += std::to_string(x + dx) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
  }
  return s;
}

} // namespace

BOOST_AUTO_TEST_SUITE(cli_bad_input)

BOOST_AUTO_TEST_CASE(missing_and_unreadable_files)
{
  const Cli_pair& p = cli_pair();
  expect_failure(match_args(in_scratch("missing.off"), p.b), 1, {"cannot open", "missing.off"});
  write_text(in_scratch("garbage.off"), "this is not a mesh\n1 2 3\n");
  expect_failure(match_args(in_scratch("garbage.off"), p.b), 1, {"garbage.off:1", "expected the OFF header"});
  write_text(in_scratch("points.xyz"), "0 0 0\n");
  expect_failure(match_args(in_scratch("points.xyz"), p.b), 1, {"points.xyz", "unknown mesh format"});
}

BOOST_AUTO_TEST_CASE(meshes_that_are_not_connected_manifold_triangle_meshes)
{
  const Cli_pair& p = cli_pair();
  // A quad (a square split in two would be fine).
  write_text(in_scratch("quad.off"), "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  expect_failure(match_args(in_scratch("quad.off"), p.b), 1, {"quad.off", "not triangles", "4 vertices"});
  // (Non-manifold edges and vertices are matched: match_handles_and_reports_damaged_meshes.)
  // Two triangles traversing their common edge in the same direction.
  write_text(in_scratch("flipped.off"), "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 0 1 3\n");
  expect_failure(match_args(in_scratch("flipped.off"), p.b), 1, {"flipped.off", "inconsistently oriented"});
  // Two closed tetrahedra.
  write_text(in_scratch("two.off"), "OFF\n8 8 0\n" + tetrahedron(0) + tetrahedron(3) +
                                        "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 4 6 5\n3 4 5 7\n3 4 7 6\n3 5 6 7\n");
  expect_failure(match_args(in_scratch("two.off"), p.b), 1, {"two.off", "2 connected components"});
  // A vertex that no face uses.
  write_text(in_scratch("isolated.off"), "OFF\n5 4 0\n" + tetrahedron(0) + "5 5 5\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  expect_failure(match_args(in_scratch("isolated.off"), p.b), 1, {"isolated.off", "vertex 4", "no face"});
}

BOOST_AUTO_TEST_CASE(malformed_text_meshes_are_named_by_file_line_and_element)
{
  // OFF and OBJ, the formats edited by hand: each problem names the file, the line and the vertex
  // or face. The tetrahedron's OFF file: header on line 1, counts on line 2, vertices on lines
  // 3-6, faces on lines 7-10.
  const Cli_pair& p = cli_pair();
  const std::string faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  auto off = [&](const std::string& name, const std::string& text) {
    write_text(in_scratch(name), text);
    return in_scratch(name);
  };
  expect_failure(match_args(off("nan.off", "OFF\n4 4 0\n0 0 0\nnan 0 0\n0 1 0\n0 0 1\n" + faces), p.b), 1,
                 {"nan.off:4:", "vertex 1", "non-finite coordinate"});
  expect_failure(match_args(off("range.off", "OFF\n4 4 0\n" + tetrahedron(0) + "3 0 2 1\n3 0 1 7\n3 0 3 2\n3 1 2 3\n"),
                            p.b),
                 1, {"range.off:8:", "face 1", "refers to vertex 7", "4 vertices"});
  expect_failure(match_args(off("repeat.off", "OFF\n4 4 0\n" + tetrahedron(0) + "3 0 2 1\n3 0 1 3\n3 0 3 3\n3 1 2 3\n"),
                            p.b),
                 1, {"repeat.off:9:", "face 2", "repeats vertex 3"});
  expect_failure(match_args(off("quad2.off", "OFF\n# a comment\n4 2 0\n" + tetrahedron(0) + "3 0 2 1\n4 0 1 2 3\n"), p.b), 1,
                 {"quad2.off:9:", "not triangles", "face 1 has 4 vertices"});
  expect_failure(match_args(off("truncated.off", "OFF\n4 4 0\n" + tetrahedron(0) + "3 0 2 1\n3 0 1 3\n"), p.b), 1,
                 {"truncated.off", "truncated", "4 faces", "after 2"});
  expect_failure(match_args(off("short.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n"), p.b), 1,
                 {"short.off", "truncated", "4 vertices", "after 2 vertices"});
  expect_failure(match_args(off("word.off", "OFF\n4 4 0\n0 0 0\n1 zero 0\n0 1 0\n0 0 1\n" + faces), p.b), 1,
                 {"word.off:4:", "vertex 1", "\"zero\" is not a number"});
  // OBJ: 1-based and negative indices, texture and normal indices skipped.
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  expect_failure(match_args(off("inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"), p.b), 1,
                 {"inf.obj:2:", "vertex 1", "non-finite"});
  expect_failure(match_args(off("range.obj", v + "f 1/1 3/3 2/2\nf 1//1 2//2 9//9\n"), p.b), 1,
                 {"range.obj:6:", "face 1", "refers to vertex 9"});
  expect_failure(match_args(off("quad.obj", "# quad\n" + v + "f 1 3 2\nf -4 -3 -2 -1\n"), p.b), 1,
                 {"quad.obj:7:", "not triangles", "face 1 has 4 vertices"});
  // A well-formed OBJ (the test pair's source, with "i/t/n", "i//n" and negative face entries)
  // gives the same mesh, vertex for vertex: the exact map evaluates to error 0.
  std::ostringstream obj;
  obj.precision(17);
  obj << "# the source of the test pair\nvt 0 0\nvn 0 0 1\n";
  for(const auto vertex : p.pair.m1.vertices()) obj << "v " << p.pair.m1.point(vertex) << "\n";
  const long long n1 = static_cast<long long>(num_vertices(p.pair.m1));
  std::size_t k = 0;
  for(const auto f : p.pair.m1.faces())
  {
    obj << "f";
    for(const auto w : vertices_around_face(p.pair.m1.halfedge(f), p.pair.m1))
    {
      const long long i = static_cast<long long>(w.idx());
      if(k % 3 == 0) obj << " " << i + 1 << "/1/1";
      else if(k % 3 == 1) obj << " " << i + 1 << "//1";
      else obj << " " << i - n1;  // counted back from the last vertex
    }
    obj << "\n";
    ++k;
  }
  write_text(in_scratch("A.obj"), obj.str());
  write_map(in_scratch("gt12.map"), p.pair.gt_12, 1);
  write_map(in_scratch("ids.vts"), identity(num_vertices(p.pair.m1)), 1);
  const Run exact = comap("eval --source " + in_scratch("A.obj") + " --target " + p.b + " --map " + in_scratch("gt12.map") +
                          " --gt-source " + in_scratch("ids.vts") + " --gt-target " + in_scratch("gt12.map"));
  BOOST_TEST_REQUIRE(exact.code == 0, exact.err);
  BOOST_TEST(exact.out.find("mean 0.0000") != std::string::npos, exact.out);
}

BOOST_AUTO_TEST_CASE(bad_maps)
{
  const Cli_pair& p = cli_pair();
  const std::size_t n1 = num_vertices(p.pair.m1), n2 = num_vertices(p.pair.m2);
  write_map(in_scratch("good21.map"), p.pair.gt_21, 1);
  std::vector<std::size_t> shorter(p.pair.gt_12.begin(), p.pair.gt_12.end() - 1);
  write_map(in_scratch("short12.map"), shorter, 1);
  const std::string init21 = " --init-21 " + in_scratch("good21.map");
  expect_failure(match_args(p.a, p.b, " --init-12 " + in_scratch("short12.map") + init21), 1,
                 {"short12.map", std::to_string(n1 - 1) + " entries", std::to_string(n1) + " vertices"});
  std::vector<std::size_t> out_of_range = p.pair.gt_12;
  out_of_range[7] = n2;  // one past the last vertex
  write_map(in_scratch("range12.map"), out_of_range, 1);
  expect_failure(match_args(p.a, p.b, " --init-12 " + in_scratch("range12.map") + init21), 1,
                 {"range12.map", "entry 7", "out of range"});
  // A 0-based file read as 1-based: its 0 is below the index base.
  write_map(in_scratch("zero12.map"), p.pair.gt_12, 0);
  expect_failure(match_args(p.a, p.b, " --init-12 " + in_scratch("zero12.map") + init21), 1,
                 {"zero12.map", "below the index base"});
  write_text(in_scratch("text12.map"), "1\n2\nthree\n");
  expect_failure(match_args(p.a, p.b, " --init-12 " + in_scratch("text12.map") + init21), 1,
                 {"text12.map:3", "expected one vertex index"});
  // Landmark files: bad lines and out-of-range pairs are named; landmarks need the automatic maps.
  write_text(in_scratch("bad.lmk"), "1 2\n3\n");
  expect_failure(match_args(p.a, p.b, " --landmarks " + in_scratch("bad.lmk")), 1,
                 {"bad.lmk:2", "two vertex indices"});
  write_text(in_scratch("range.lmk"), "# source target\n1 " + std::to_string(n2 + 1) + "\n");
  expect_failure(match_args(p.a, p.b, " --landmarks " + in_scratch("range.lmk")), 1, {"range.lmk:2", "out of range"});
  expect_failure(match_args(p.a, p.b, " --landmarks " + in_scratch("missing.lmk")), 1, {"missing.lmk"});
  write_text(in_scratch("good.lmk"), "1 1\n");
  expect_failure(match_args(p.a, p.b, " --landmarks " + in_scratch("good.lmk") + " --init-12 " +
                                          in_scratch("range12.map") + init21),
                 2, {"--landmarks"});
  // eval: ground-truth lists of different lengths.
  write_map(in_scratch("ids.vts"), identity(n1), 1);
  write_map(in_scratch("gt_short.vts"), shorter, 1);
  write_map(in_scratch("gt12.map"), p.pair.gt_12, 1);
  expect_failure("eval --source " + p.a + " --target " + p.b + " --map " + in_scratch("gt12.map") + " --gt-source " +
                     in_scratch("ids.vts") + " --gt-target " + in_scratch("gt_short.vts"),
                 1, {"samples"});
}

BOOST_AUTO_TEST_CASE(bad_options)
{
  const Cli_pair& p = cli_pair();
  // Settings by name (--set, --settings): the setting, its type or range, and the closest name.
  expect_failure(match_args(p.a, p.b, " --set number_of_candidates=abc"), 2, {"number_of_candidates", "integer"});
  expect_failure(match_args(p.a, p.b, " --set unary_weight=-1"), 2, {"unary_weight", "out of its range [0, inf)"});
  expect_failure(match_args(p.a, p.b, " --set ring_schedule=3,,2"), 2, {"ring_schedule", "expected a number"});
  expect_failure(match_args(p.a, p.b, " --set use_coupling=maybe"), 2, {"use_coupling", "true or false"});
  expect_failure(match_args(p.a, p.b, " --set distance_oracle=fast"), 2, {"distance_oracle", "automatic, dense or local"});
  expect_failure(match_args(p.a, p.b, " --set number_of_repair_passes=-1"), 2, {"number_of_repair_passes", "[0, 100]"});
  expect_failure(match_args(p.a, p.b, " --set tear_threshold=0"), 2, {"tear_threshold", "(0, inf)"});
  expect_failure(match_args(p.a, p.b, " --set tear_area_fraction=1.5"), 2, {"tear_area_fraction", "out of its range"});
  expect_failure(match_args(p.a, p.b, " --set numbr_of_candidates=3"), 2,
                 {"unknown setting \"numbr_of_candidates\"", "did you mean \"number_of_candidates\""});
  expect_failure(match_args(p.a, p.b, " --set number_of_candidates"), 2, {"--set needs NAME=VALUE"});
  write_text(in_scratch("typo.json"), "{\"number_of_candidate\": 30}\n");
  expect_failure(match_args(p.a, p.b, " --settings " + in_scratch("typo.json")), 1,
                 {"number_of_candidate", "did you mean \"number_of_candidates\""});
  expect_failure(match_args(p.a, p.b, " --settings " + in_scratch("missing.json")), 1, {"missing.json"});
  expect_failure(match_args(p.a, p.b, " --index-base 2"), 2, {"--index-base"});
  // The expert flags of earlier versions are gone: settings go through --set.
  expect_failure(match_args(p.a, p.b, " --candidates 30"), 2, {"unknown option --candidates"});
  expect_failure(match_args(p.a, p.b, " --frobnicate"), 2, {"unknown option --frobnicate"});
  expect_failure(match_args(p.a, p.b, " --init-12 " + in_scratch("x.map")), 2, {"--init-21"});
  expect_failure("match " + p.a + " " + p.b + " --quiet", 2, {"--out-12"});
  expect_failure("match " + p.a + " --out-12 a --out-21 b", 2, {"two meshes"});
  expect_failure("match " + p.a + " " + p.b + " --out-12 /nonexistent/dir/a.map --out-21 b.map", 1,
                 {"/nonexistent/dir", "does not exist"});
  expect_failure("frobnicate", 2, {"unknown command"});
  expect_failure("bench --data " + in_scratch("nothing") + " --out " + in_scratch("b"), 1, {"not a directory"});
  write_map(in_scratch("gt12.map"), p.pair.gt_12, 1);
  expect_failure("transfer --source " + p.a + " --target " + p.b + " --map-12 " + in_scratch("gt12.map") + " --out " +
                     in_scratch("t.ply") + " --texture " + p.a,
                 1, {"PNG"});
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(cli_outputs)

BOOST_AUTO_TEST_CASE(an_output_never_names_an_input_or_another_output)
{
  const Cli_pair& p = cli_pair();
  const std::string target_before = read_text(p.b), source_before = read_text(p.a);
  write_map(in_scratch("gt12.map"), p.pair.gt_12, 1);
  write_map(in_scratch("gt21.map"), p.pair.gt_21, 1);
  const std::string init = " --init-12 " + in_scratch("gt12.map") + " --init-21 " + in_scratch("gt21.map");
  auto match = [&](const std::string& out_12, const std::string& out_21, const std::string& extra = "") {
    return "match " + p.a + " " + p.b + " --out-12 " + out_12 + " --out-21 " + out_21 + " --quiet" + extra;
  };
  // The target mesh itself, through another spelling of its path, a symbolic link and a hard link.
  expect_failure(match(p.b, in_scratch("x21.map")), 2, {"--out-12", "TARGET", "never replaces an input"});
  std::filesystem::create_directories(in_scratch("sub"));
  expect_failure(match(in_scratch("x12.map"), in_scratch("sub/../B.off")), 2, {"--out-21", "TARGET"});
  std::filesystem::remove(in_scratch("link.off"));
  std::filesystem::create_symlink(p.b, in_scratch("link.off"));
  expect_failure(match(in_scratch("link.off"), in_scratch("x21.map")), 2, {"--out-12", "link.off", "TARGET"});
  std::filesystem::remove(in_scratch("hard.off"));
  std::filesystem::create_hard_link(p.a, in_scratch("hard.off"));
  expect_failure(match(in_scratch("x12.map"), in_scratch("hard.off")), 2, {"--out-21", "hard.off", "SOURCE"});
  // Initial maps, statistics and settings files.
  expect_failure(match(in_scratch("gt12.map"), in_scratch("x21.map"), init), 2, {"--out-12", "--init-12"});
  expect_failure(match(in_scratch("x12.map"), in_scratch("x21.map"), init + " --stats " + in_scratch("gt21.map")), 2,
                 {"--stats", "--init-21"});
  write_text(in_scratch("expert.json"), "{\"number_of_candidates\": 12}\n");
  expect_failure(match(in_scratch("x12.map"), in_scratch("x21.map"),
                       " --settings " + in_scratch("expert.json") + " --stats " + in_scratch("expert.json")),
                 2, {"--stats", "--settings"});
  // Two outputs of one run.
  expect_failure(match(in_scratch("same.map"), in_scratch("same.map")), 2, {"--out-12", "--out-21", "each output"});
  expect_failure(match(in_scratch("same.map"), in_scratch("./sub/../same.map")), 2, {"--out-12", "--out-21"});
  // transfer: the coloured source over the source mesh, the target's file over the target mesh.
  expect_failure("transfer --source " + p.a + " --target " + p.b + " --map-12 " + in_scratch("gt12.map") + " --out " +
                     p.a,
                 2, {"--out", "--source"});
  std::filesystem::copy_file(p.b, in_scratch("T_target.off"), std::filesystem::copy_options::overwrite_existing);
  expect_failure("transfer --source " + p.a + " --target " + in_scratch("T_target.off") + " --map-12 " +
                     in_scratch("gt12.map") + " --out " + in_scratch("T.off"),
                 2, {"--target", "target's output"});
  // bench: maps written under --out are never the initial maps of --init.
  std::filesystem::create_directories(in_scratch("run/maps"));
  std::filesystem::create_directories(in_scratch("data/off"));
  expect_failure("bench --data " + in_scratch("data") + " --init " + in_scratch("run/maps") + " --out " + in_scratch("run"),
                 2, {"--out (its maps)", "--init"});
  // Nothing was written over the inputs.
  BOOST_TEST((read_text(p.b) == target_before));
  BOOST_TEST((read_text(p.a) == source_before));
  BOOST_TEST(read_text(in_scratch("expert.json")) == "{\"number_of_candidates\": 12}\n");
}

BOOST_AUTO_TEST_CASE(a_run_killed_before_its_outputs_are_complete_leaves_the_previous_ones)
{
  // The test hook kills comap after both maps and the statistics were written to temporary files
  // and before the first rename: the previous outputs stay whole, and the leftovers are hidden
  // files that no output name matches.
  const Cli_pair& p = cli_pair();
  const std::string dir = in_scratch("killed");
  std::filesystem::create_directories(dir);
  write_text(dir + "/o12.map", "previous 12\n");
  write_text(dir + "/o21.map", "previous 21\n");
  write_text(dir + "/stats.json", "previous stats\n");
  const std::string arguments = "match " + p.a + " " + p.b + " --out-12 " + dir + "/o12.map --out-21 " + dir +
                                "/o21.map --stats " + dir + "/stats.json" + fast_options() +
                                " --set use_refinement=false";
  const Run killed = comap(arguments, "COMAP_TEST_KILL_BEFORE_COMMIT=1");
  BOOST_TEST(killed.code == 128 + 9, "comap was not killed by the hook: " << killed.code << " " << killed.err);
  BOOST_TEST(read_text(dir + "/o12.map") == "previous 12\n");
  BOOST_TEST(read_text(dir + "/o21.map") == "previous 21\n");
  BOOST_TEST(read_text(dir + "/stats.json") == "previous stats\n");
  std::size_t leftovers = 0;
  for(const auto& e : std::filesystem::directory_iterator(dir))
  {
    const std::string name = e.path().filename().string();
    if(name == "o12.map" || name == "o21.map" || name == "stats.json") continue;
    ++leftovers;
    BOOST_TEST(name.front() == '.', name);
    BOOST_TEST(name.find(".tmp-") != std::string::npos, name);
    BOOST_TEST(read_text(e.path().string()).size() > 0u, name);  // written completely, then killed
  }
  BOOST_TEST(leftovers == 3u);
  // The same run without the hook replaces all three.
  const Run done = comap(arguments);
  BOOST_TEST_REQUIRE(done.code == 0, done.err);
  BOOST_TEST(read_map(dir + "/o12.map", 1).size() == num_vertices(p.pair.m1));
  BOOST_TEST(read_map(dir + "/o21.map", 1).size() == num_vertices(p.pair.m2));
  BOOST_TEST(read_text(dir + "/stats.json").front() == '{');
}

BOOST_AUTO_TEST_SUITE_END()
