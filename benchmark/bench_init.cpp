// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Benchmark of the automatic initial maps (automatic_initialization.h) on the shared FAUST_r and
// TOSCA_r test pairs: accuracy against the ground truth, mirror flips and time per pair.
//
//   bench_init [options]
//     --dataset FAUST_r|TOSCA_r|both   (default both)
//     --limit N        only the first N pairs of each dataset (after --stride)
//     --stride S       every S-th pair (a spread-out subset)
//     --jobs J         J pairs at once, each sequential (default 1: one pair at a time with
//                      CGAL::Parallel_tag; use J = 1 for the timings)
//     --no-eval        maps and timings only
//     --csv FILE       per-direction rows to FILE
//     --pairs FILE     pairs to run instead of the dataset's test_pairs.txt
//     --verbose        the method's progress messages
//     --nn             nearest-neighbour search: blocked GEMM vs CGAL Kd_tree
//     settings of the method: --cands k0:wo:wc,... --sel --kf --step --eig --wl --hks --wks --nwks
//       --sw --ssmooth --nops --normgrad --procrustes --coupled --zbij --samples --zdw --zdr
//       --gstep --pass --repairs --drepair --maxpasses
//
// Error of a map T from A to B, per ground-truth sample k (5000 per shape):
//   err_k = d_B(T(A.vts[k]), B.vts[k]) / sqrt(area(B)),
// d_B the fast-marching geodesic distance on B (all pairs, cached in /tmp/smc_bench_init_cache).
// The symmetry-tolerant error takes per sample the minimum with the error against B.sym.vts; a
// direction counts as mirror-flipped when its mean error against the mirrored ground truth is
// below half its mean error against the direct one.

#include <CGAL/Surface_mesh_correspondence/automatic_initialization.h>
#include <CGAL/Surface_mesh_correspondence/distance_oracle.h>
#include <CGAL/Surface_mesh_correspondence/map_io.h>

#include "bench_util.h"

#include <CGAL/Search_traits_d.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Epick_d.h>

#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
using smc_bench::Mesh;
using smc_bench::Report;
using smc_bench::Timer;

namespace {

struct Options
{
  std::string dataset = "both";
  int limit = 0, stride = 1, jobs = 1;
  bool evaluate = true, nn = false;
  std::string csv, pairs_file;
  smc::internal::Initialization_settings settings;
};

struct Shape
{
  Mesh mesh;
  smc::Vertex_index_map_vector vts, sym;
};

struct Direction
{
  std::string source, target;
  std::vector<std::size_t> map;
  double seconds = 0;  // of the pair (both directions)
  // filled by the evaluation
  double error = 0, sym_error = 0, tolerant_error = 0;
  double direct_ok = 0, mirror_ok = 0;  // fractions of samples within 0.05 of the GT / mirrored GT
};

std::string cache_directory() { return "/tmp/smc_bench_init_cache"; }

Shape load_shape(const std::string& dir, const std::string& name)
{
  Shape s;
  if(!smc_bench::read_mesh(dir + "/off/" + name + ".off", s.mesh))
    throw std::runtime_error("cannot read " + dir + "/off/" + name + ".off");
  s.vts = smc::read_vertex_indices(dir + "/corres/" + name + ".vts", 1);
  s.sym = smc::read_vertex_indices(dir + "/corres/" + name + ".sym.vts", 1);
  return s;
}

// All-pairs fast-marching distances of a shape, from the disk cache or computed (and cached).
std::vector<float> distance_matrix(const std::string& dataset, const std::string& name, const Mesh& mesh)
{
  const std::size_t n = num_vertices(mesh);
  const std::string file = cache_directory() + "/" + dataset + "_" + name + ".f32";
  std::vector<float> d(n * n);
  {
    std::ifstream in(file, std::ios::binary);
    if(in && in.read(reinterpret_cast<char*>(d.data()), std::streamsize(d.size() * sizeof(float))))
      return d;
  }
  const smc::internal::Indexed_mesh m = smc::internal::make_indexed_mesh(mesh);
  const smc::Dense_distance_oracle o = smc::Dense_distance_oracle::build<CGAL::Parallel_tag>(m);
  for(std::size_t i = 0; i < n; ++i) std::copy(o.row(int(i)), o.row(int(i)) + n, d.begin() + i * n);
  mkdir(cache_directory().c_str(), 0755);
  std::ofstream out(file, std::ios::binary);
  out.write(reinterpret_cast<const char*>(d.data()), std::streamsize(d.size() * sizeof(float)));
  return d;
}

double mesh_area(const Mesh& m) { return CGAL::to_double(CGAL::Polygon_mesh_processing::area(m)); }

std::vector<std::pair<std::string, std::string> > read_pairs(const std::string& file)
{
  std::ifstream in(file);
  if(!in) throw std::runtime_error("cannot read " + file);
  std::vector<std::pair<std::string, std::string> > pairs;
  std::string a, b;
  while(in >> a >> b) pairs.emplace_back(a, b);
  return pairs;
}

struct Summary
{
  std::string dataset;
  int pairs = 0, directions = 0, flipped = 0, sym_better = 0;
  double error = 0, tolerant = 0, seconds = 0, max_seconds = 0, spectra = 0, fmap = 0, zoomout = 0;
  double cycle = 0, fixed = 0;
};

Summary run_dataset(const std::string& dataset, const Options& opt, std::ofstream* csv)
{
  const std::string dir = smc_bench::data_directory() + "/" + dataset;
  std::vector<std::pair<std::string, std::string> > all =
      read_pairs(opt.pairs_file.empty() ? dir + "/test_pairs.txt" : opt.pairs_file), pairs;
  for(std::size_t i = 0; i < all.size(); i += std::size_t(std::max(1, opt.stride))) pairs.push_back(all[i]);
  if(opt.limit > 0 && pairs.size() > std::size_t(opt.limit)) pairs.resize(std::size_t(opt.limit));

  std::map<std::string, Shape> shapes;
  for(const auto& p : pairs)
    for(const std::string& name : {p.first, p.second})
      if(!shapes.count(name)) shapes[name] = load_shape(dir, name);

  Summary summary;
  summary.dataset = dataset;
  summary.pairs = int(pairs.size());
  std::vector<Direction> directions(2 * pairs.size());
  std::vector<smc::Automatic_initialization_result> results(pairs.size());
  std::atomic<std::size_t> next(0);
  std::mutex print_mutex;
  auto worker = [&](bool parallel) {
    for(;;)
    {
      const std::size_t i = next++;
      if(i >= pairs.size()) return;
      const Shape& A = shapes[pairs[i].first];
      const Shape& B = shapes[pairs[i].second];
      Direction& ab = directions[2 * i];
      Direction& ba = directions[2 * i + 1];
      ab.source = ba.target = pairs[i].first;
      ab.target = ba.source = pairs[i].second;
      Timer t;
      smc::internal::Mesh_requirements req;
      req.allow_several_components = false;
      // The same steps as automatic_initial_maps(), with all settings exposed.
      const smc::internal::Initialization_settings& s = opt.settings;
      const int k = smc::internal::initialization_number_of_eigenpairs(s);
      smc::Automatic_initialization_result r;
      auto run = [&](auto tag) {
        typedef decltype(tag) Tag;
        smc::internal::Indexed_mesh ma = smc::internal::make_indexed_mesh(A.mesh, CGAL::parameters::default_values(), req, "A");
        smc::internal::Indexed_mesh mb = smc::internal::make_indexed_mesh(B.mesh, CGAL::parameters::default_values(), req, "B");
        std::unique_ptr<smc::Laplace_beltrami_spectrum> sa, sb;
        Eigen::MatrixXd da, db;
        auto pa = [&] {
          sa.reset(new smc::Laplace_beltrami_spectrum(ma, smc::parameters::number_of_eigenpairs(k)));
          da = smc::internal::initialization_descriptors<CGAL::Sequential_tag>(ma, *sa, s);
        };
        auto pb = [&] {
          sb.reset(new smc::Laplace_beltrami_spectrum(mb, smc::parameters::number_of_eigenpairs(k)));
          db = smc::internal::initialization_descriptors<CGAL::Sequential_tag>(mb, *sb, s);
        };
        if(std::is_same<Tag, CGAL::Parallel_tag>::value)
          tbb::parallel_invoke(pa, pb);
        else
        {
          pa();
          pb();
        }
        const double prep = t.seconds();
        smc::internal::Initialization_shape a{&ma, sa.get(), &da}, b{&mb, sb.get(), &db};
        r = smc::internal::automatic_initial_maps<Tag>(a, b, s, ab.map, ba.map);
        r.spectra_seconds = prep;
      };
      if(parallel)
        run(CGAL::Parallel_tag());
      else
        run(CGAL::Sequential_tag());
      ab.seconds = ba.seconds = t.seconds();
      results[i] = r;
      std::lock_guard<std::mutex> lock(print_mutex);
      std::cerr << "  " << dataset << " pair " << i + 1 << "/" << pairs.size() << " " << ab.source << " "
                << ab.target << ": " << Report::num(ab.seconds, 2) << " s (spectra "
                << Report::num(r.spectra_seconds, 2) << ", fmap " << Report::num(r.functional_map_seconds, 2)
                << ", zoomout " << Report::num(r.zoomout_seconds, 2) << "), cycle "
                << Report::num(r.cycle_error, 4) << ", orientation " << Report::num(r.orientation_agreement, 3)
                << " sign " << r.orientation_sign << "\n";
    }
  };
  if(opt.jobs <= 1)
    worker(true);
  else
  {
    std::vector<std::thread> threads;
    for(int j = 0; j < opt.jobs; ++j) threads.emplace_back(worker, false);
    for(auto& th : threads) th.join();
  }
  for(std::size_t i = 0; i < pairs.size(); ++i)
  {
    const auto& r = results[i];
    summary.seconds += directions[2 * i].seconds;
    summary.max_seconds = std::max(summary.max_seconds, directions[2 * i].seconds);
    summary.spectra += r.spectra_seconds;
    summary.fmap += r.functional_map_seconds;
    summary.zoomout += r.zoomout_seconds;
    summary.cycle += r.cycle_error;
    summary.fixed += r.cycle_fixed_fraction;
  }
  const double np = std::max<double>(1, pairs.size());
  summary.seconds /= np;
  summary.spectra /= np;
  summary.fmap /= np;
  summary.zoomout /= np;
  summary.cycle /= np;
  summary.fixed /= np;
  summary.directions = int(directions.size());
  if(!opt.evaluate) return summary;

  // Evaluation, one target shape at a time.
  std::map<std::string, std::vector<std::size_t> > by_target;
  for(std::size_t i = 0; i < directions.size(); ++i) by_target[directions[i].target].push_back(i);
  for(const auto& entry : by_target)
  {
    const Shape& B = shapes[entry.first];
    const std::vector<float> D = distance_matrix(dataset, entry.first, B.mesh);
    const std::size_t n = num_vertices(B.mesh);
    const double scale = 1.0 / std::sqrt(mesh_area(B.mesh));
    for(std::size_t i : entry.second)
    {
      Direction& d = directions[i];
      const Shape& A = shapes[d.source];
      double e = 0, es = 0, et = 0;
      const std::size_t m = std::min(A.vts.size(), B.vts.size());
      for(std::size_t k = 0; k < m; ++k)
      {
        const std::size_t y = d.map[A.vts[k]];
        const double direct = D[y * n + B.vts[k]] * scale, mirrored = D[y * n + B.sym[k]] * scale;
        e += direct;
        es += mirrored;
        if(direct < 0.05) d.direct_ok += 1;
        else if(mirrored < 0.05) d.mirror_ok += 1;
        et += std::min(direct, mirrored);
      }
      d.error = e / double(m);
      d.sym_error = es / double(m);
      d.tolerant_error = et / double(m);
      d.direct_ok /= double(m);
      d.mirror_ok /= double(m);
    }
  }
  for(const Direction& d : directions)
  {
    summary.error += d.error;
    summary.tolerant += d.tolerant_error;
    if(d.sym_error < 0.5 * d.error) ++summary.flipped;
    if(d.sym_error < d.error) ++summary.sym_better;
    if(csv)
      *csv << dataset << "," << d.source << "," << d.target << "," << d.error << "," << d.sym_error << ","
           << d.tolerant_error << "," << d.seconds << "\n";
  }
  summary.error /= std::max<double>(1, directions.size());
  summary.tolerant /= std::max<double>(1, directions.size());
  // The worst directions, for inspection.
  std::vector<std::size_t> order(directions.size());
  for(std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return directions[a].error > directions[b].error; });
  std::cerr << "  worst directions:";
  for(std::size_t i = 0; i < std::min<std::size_t>(8, order.size()); ++i)
    std::cerr << " " << directions[order[i]].source << "->" << directions[order[i]].target << " "
              << Report::num(directions[order[i]].error, 3) << "/" << Report::num(directions[order[i]].sym_error, 3)
              << " (ok " << Report::num(directions[order[i]].direct_ok, 2) << ", mirror-ok "
              << Report::num(directions[order[i]].mirror_ok, 2) << ")";
  std::cerr << "\n";
  return summary;
}

// Nearest-neighbour search in spectral embeddings: blocked GEMM brute force vs CGAL's Kd_tree.
void nn_benchmark()
{
  Mesh a, b;
  const std::string dir = smc_bench::data_directory() + "/FAUST_r/off/";
  if(!smc_bench::read_mesh(dir + "tr_reg_000.off", a) || !smc_bench::read_mesh(dir + "tr_reg_001.off", b))
  {
    std::cerr << "FAUST_r is missing\n";
    return;
  }
  const smc::Laplace_beltrami_spectrum sa(a, smc::parameters::number_of_eigenpairs(120));
  const smc::Laplace_beltrami_spectrum sb(b, smc::parameters::number_of_eigenpairs(120));
  Report report({"dimension", "queries", "data", "method", "threads", "seconds"});
  for(int d : {10, 30, 60, 120})
  {
    const Eigen::MatrixXd q = smc::internal::unit_area_basis(sa, d), x = smc::internal::unit_area_basis(sb, d);
    std::vector<int> out(std::size_t(q.rows()));
    double best_seq = 1e9, best_par = 1e9;
    for(int r = 0; r < 3; ++r)
    {
      Timer t;
      smc::internal::Nearest_neighbor_search s(x);
      s.query<CGAL::Sequential_tag>(q, out.data());
      best_seq = std::min(best_seq, t.seconds());
      t.reset();
      smc::internal::Nearest_neighbor_search s2(x);
      s2.query<CGAL::Parallel_tag>(q, out.data());
      best_par = std::min(best_par, t.seconds());
    }
    report.add({std::to_string(d), std::to_string(q.rows()), std::to_string(x.rows()), "blocked GEMM", "1",
                Report::num(best_seq, 4)});
    report.add({std::to_string(d), std::to_string(q.rows()), std::to_string(x.rows()), "blocked GEMM", "2",
                Report::num(best_par, 4)});
    // CGAL Kd_tree (sliding midpoint), exact 1-NN.
    typedef CGAL::Epick_d<CGAL::Dynamic_dimension_tag> K;
    typedef K::Point_d Point_d;
    typedef CGAL::Search_traits_d<K> Traits;
    typedef CGAL::Orthogonal_k_neighbor_search<Traits> Search;
    std::vector<Point_d> pts;
    for(Eigen::Index i = 0; i < x.rows(); ++i) pts.emplace_back(d, x.row(i).data(), x.row(i).data() + d);
    Timer t;
    Search::Tree tree(pts.begin(), pts.end());
    tree.build();
    int mismatches = 0;
    Eigen::MatrixXd qr = q;  // row-major copy not needed: rows are read element-wise
    for(Eigen::Index i = 0; i < q.rows(); ++i)
    {
      std::vector<double> c(static_cast<std::size_t>(d));
      for(int j = 0; j < d; ++j) c[std::size_t(j)] = qr(i, j);
      Search search(tree, Point_d(d, c.begin(), c.end()), 1);
      const Point_d p = search.begin()->first;
      if(std::abs(p[0] - x(out[std::size_t(i)], 0)) > 1e-6) ++mismatches;
    }
    report.add({std::to_string(d), std::to_string(q.rows()), std::to_string(x.rows()),
                "CGAL Kd_tree" + std::string(mismatches ? " (" + std::to_string(mismatches) + " differ)" : ""),
                "1", Report::num(t.seconds(), 4)});
  }
  report.print();
}

bool parse(int argc, char** argv, Options& o)
{
  auto& s = o.settings;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if(i + 1 >= argc) throw std::runtime_error("missing value after " + a);
      return argv[++i];
    };
    if(a == "--dataset") o.dataset = next();
    else if(a == "--limit") o.limit = std::stoi(next());
    else if(a == "--stride") o.stride = std::stoi(next());
    else if(a == "--jobs") o.jobs = std::stoi(next());
    else if(a == "--no-eval") o.evaluate = false;
    else if(a == "--csv") o.csv = next();
    else if(a == "--pairs") o.pairs_file = next();
    else if(a == "--verbose") s.verbose = true;
    else if(a == "--nn") o.nn = true;
    else if(a == "--cands")
    {
      // k0:wo:wc,k0:wo:wc,...
      s.candidates.clear();
      std::stringstream list(next());
      std::string item;
      while(std::getline(list, item, ','))
      {
        smc::internal::Fit_candidate c{};
        if(std::sscanf(item.c_str(), "%d:%lf:%lf", &c.basis_size, &c.orientation_weight, &c.commutativity_weight) != 3)
          throw std::runtime_error("bad candidate " + item);
        s.candidates.push_back(c);
      }
    }
    else if(a == "--sel") s.selection_size = std::stoi(next());
    else if(a == "--sw") s.signed_descriptor_weight = std::stod(next());
    else if(a == "--ssmooth") s.signed_descriptor_smoothing = std::stoi(next());
    else if(a == "--zdw") s.zoomout_descriptor_weight = std::stod(next());
    else if(a == "--zdr") s.zoomout_descriptor_final_ratio = std::stod(next());
    else if(a == "--zdall") s.zoomout_signed_features_only = std::stoi(next()) == 0;
    else if(a == "--procrustes") s.procrustes = std::stoi(next()) != 0;
    else if(a == "--kf") s.zoomout_final_size = std::stoi(next());
    else if(a == "--step") s.zoomout_step = std::stoi(next());
    else if(a == "--gstep") s.zoomout_growth_step = std::stoi(next());
    else if(a == "--pass") s.zoomout_pass_size = std::stoi(next());
    else if(a == "--repairs") s.tear_repair_passes = std::stoi(next());
    else if(a == "--drepair") s.distortion_repair_passes = std::stoi(next());
    else if(a == "--maxpasses") s.maximum_passes = std::stoi(next());
    else if(a == "--tdtol") s.tear_repair_distortion_tolerance = std::stod(next());
    else if(a == "--eig") s.number_of_eigenpairs = std::stoi(next());
    else if(a == "--wl") s.weights.laplacian = std::stod(next());
    else if(a == "--hks") s.hks_weight = std::stod(next());
    else if(a == "--wks") s.wks_weight = std::stod(next());
    else if(a == "--nwks") s.number_of_wks_energies = std::stoi(next());
    else if(a == "--nops") s.number_of_operator_descriptors = std::stoi(next());
    else if(a == "--normgrad") s.normalize_orientation_gradients = std::stoi(next()) != 0;
    else if(a == "--coupled") s.coupled_zoomout = std::stoi(next()) != 0;
    else if(a == "--zbij") s.zoomout_bijectivity_weight = std::stod(next());
    else if(a == "--samples") s.zoomout_number_of_samples = std::stoi(next());
    else
    {
      std::cerr << "unknown option " << a << "\n";
      return false;
    }
  }
  return true;
}

} // namespace

int main(int argc, char** argv)
{
  Options opt;
  try
  {
    if(!parse(argc, argv, opt)) return 1;
  }
  catch(const std::exception& e)
  {
    std::cerr << e.what() << "\n";
    return 1;
  }
  if(opt.nn)
  {
    nn_benchmark();
    return 0;
  }
  std::vector<std::string> datasets;
  if(opt.dataset == "both")
    datasets = {"FAUST_r", "TOSCA_r"};
  else
    datasets = {opt.dataset};
  std::unique_ptr<std::ofstream> csv;
  if(!opt.csv.empty())
  {
    csv.reset(new std::ofstream(opt.csv));
    *csv << "dataset,source,target,error,sym_error,tolerant_error,pair_seconds\n";
  }
  Report report({"dataset", "pairs", "directions", "mean_error", "sym_tolerant_error", "flipped",
                 "sym_better", "seconds_per_pair", "max_seconds", "spectra_s", "fmap_s", "zoomout_s",
                 "cycle_error", "cycle_fixed"});
  for(const std::string& d : datasets)
  {
    try
    {
      const Summary s = run_dataset(d, opt, csv.get());
      report.add({s.dataset, std::to_string(s.pairs), std::to_string(s.directions), Report::num(s.error, 4),
                  Report::num(s.tolerant, 4),
                  Report::num(double(s.flipped) / std::max(1, s.directions), 4),
                  Report::num(double(s.sym_better) / std::max(1, s.directions), 4), Report::num(s.seconds, 3),
                  Report::num(s.max_seconds, 3), Report::num(s.spectra, 3), Report::num(s.fmap, 3),
                  Report::num(s.zoomout, 3), Report::num(s.cycle, 4), Report::num(s.fixed, 4)});
    }
    catch(const std::exception& e)
    {
      std::cerr << d << ": " << e.what() << "\n";
      return 1;
    }
  }
  report.print();
  return 0;
}
