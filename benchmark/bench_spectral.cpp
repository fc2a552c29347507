// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Benchmark of the Laplace-Beltrami operator, its spectrum and the HKS / WKS descriptors.
//
//   bench_spectral [sizes...]      time and peak memory at about 5k, 25k, 100k vertices
//   bench_spectral --sweep [n]     eigensolver settings (Krylov dimension, shift, tolerance)
//   bench_spectral --accuracy      sphere eigenvalue errors with and without intrinsic Delaunay
//
// Each section prints CSV and a table (see bench_util.h).

#include <CGAL/Surface_mesh_correspondence/heat_kernel_signature.h>
#include <CGAL/Surface_mesh_correspondence/laplacian.h>
#include <CGAL/Surface_mesh_correspondence/spectrum.h>
#include <CGAL/Surface_mesh_correspondence/wave_kernel_signature.h>

#include "bench_util.h"
#include "../test/test_meshes.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <iostream>
#include <string>
#include <vector>

namespace smc = CGAL::Surface_mesh_correspondence;
namespace params = CGAL::Surface_mesh_correspondence::parameters;
using smc_bench::Report;
using smc_bench::Timer;

namespace {

// Best of `repeats` runs of f (the first run also measures the peak memory).
template <typename F>
double best_time(int repeats, const F& f, double* peak_mib = nullptr)
{
  double best = 1e300;
  for(int r = 0; r < repeats; ++r)
  {
    if(r == 0) smc_bench::reset_peak_memory();
    const double before = smc_bench::current_memory_mib();
    Timer t;
    f();
    best = std::min(best, t.seconds());
    if(r == 0 && peak_mib) *peak_mib = smc_bench::peak_memory_mib() - before;
  }
  return best;
}

int count_negative_weights(const Eigen::SparseMatrix<double>& L)
{
  int count = 0;
  for(Eigen::Index j = 0; j < L.outerSize(); ++j)
    for(Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it)
      if(it.row() < it.col() && it.value() > 1e-10 * std::abs(L.coeff(it.row(), it.row()))) ++count;
  return count;
}

void timings(const std::vector<int>& sizes)
{
  Report report({"vertices", "step", "threads", "seconds", "peak_MiB", "notes"});
  for(int size : sizes)
  {
    std::string description;
    const smc_bench::Mesh mesh = smc_bench::benchmark_mesh(size, &description);
    const int n = static_cast<int>(num_vertices(mesh));
    std::cout << "mesh: " << description << ", " << n << " vertices\n" << std::flush;
    const int repeats = n < 50000 ? 3 : 1;
    const smc::internal::Indexed_mesh im = smc::internal::make_indexed_mesh(mesh);
    const std::string vs = std::to_string(n);
    double peak = 0;
    double t = best_time(repeats, [&] { smc::internal::make_indexed_mesh(mesh); }, &peak);
    report.add({vs, "indexed_mesh", "1", Report::num(t, 4), Report::num(peak, 1), ""});
    smc::Laplace_beltrami_matrices plain, idt;
    t = best_time(repeats, [&] { plain = smc::internal::laplace_beltrami_matrices(im, false); }, &peak);
    report.add({vs, "laplacian", "1", Report::num(t, 4), Report::num(peak, 1),
                "negative weights " + std::to_string(count_negative_weights(plain.stiffness_matrix))});
    t = best_time(repeats, [&] { idt = smc::internal::laplace_beltrami_matrices(im, true); }, &peak);
    report.add({vs, "laplacian_idt", "1", Report::num(t, 4), Report::num(peak, 1),
                std::to_string(idt.number_of_flips) + " flips; negative weights " +
                    std::to_string(count_negative_weights(idt.stiffness_matrix))});
    for(bool use_idt : {true, false})
    {
      std::unique_ptr<smc::Laplace_beltrami_spectrum> spectrum;
      t = best_time(repeats, [&] {
        spectrum.reset(new smc::Laplace_beltrami_spectrum(
            im, params::use_intrinsic_delaunay(use_idt, params::number_of_eigenpairs(100))));
      }, &peak);
      const auto& st = spectrum->solver_statistics();
      report.add({vs, use_idt ? "spectrum_100_idt" : "spectrum_100", "1", Report::num(t, 4),
                  Report::num(peak, 1),
                  "ncv " + std::to_string(st.krylov_dimension) + ", restarts " +
                      std::to_string(st.restarts) + ", solves " + std::to_string(st.operations)});
      if(!use_idt) continue;
      Eigen::MatrixXd d;
      t = best_time(repeats, [&] { d = smc::heat_kernel_signature(*spectrum); }, &peak);
      report.add({vs, "hks_16", "1", Report::num(t, 4), Report::num(peak, 1), ""});
      t = best_time(repeats, [&] { d = smc::heat_kernel_signature<CGAL::Parallel_tag>(*spectrum); });
      report.add({vs, "hks_16", "tbb", Report::num(t, 4), "", ""});
      t = best_time(repeats, [&] { d = smc::wave_kernel_signature(*spectrum); }, &peak);
      report.add({vs, "wks_100", "1", Report::num(t, 4), Report::num(peak, 1), ""});
      t = best_time(repeats, [&] { d = smc::wave_kernel_signature<CGAL::Parallel_tag>(*spectrum); });
      report.add({vs, "wks_100", "tbb", Report::num(t, 4), "", ""});
    }
  }
  report.print();
}

void sweep(int size)
{
  std::string description;
  const smc_bench::Mesh mesh = smc_bench::benchmark_mesh(size, &description);
  const smc::internal::Indexed_mesh im = smc::internal::make_indexed_mesh(mesh);
  const smc::Laplace_beltrami_matrices lb = smc::internal::laplace_beltrami_matrices(im, true);
  std::cout << "mesh: " << description << ", " << im.number_of_vertices() << " vertices\n";
  const int k = 100;
  // Reference: a tight tolerance.
  smc::internal::Eigensolver_settings reference_settings;
  reference_settings.tolerance = 1e-13;
  reference_settings.krylov_dimension = 3 * k;
  Eigen::VectorXd reference;
  Eigen::MatrixXd vectors;
  smc::internal::laplace_beltrami_eigenpairs(lb.stiffness_matrix, lb.mass, im.component,
                                             im.number_of_components, k, reference_settings,
                                             reference, vectors);
  const int repeats = im.number_of_vertices() < 50000 ? 3 : 1;
  Report report({"ncv", "shift", "tolerance", "seconds", "restarts", "solves", "max_rel_eigenvalue_error"});
  auto sci = [](double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.1e", x);
    return std::string(buffer);
  };
  auto run = [&](int ncv, double shift, double tolerance) {
    smc::internal::Eigensolver_settings s;
    s.krylov_dimension = ncv;
    s.relative_shift = shift;
    s.tolerance = tolerance;
    smc::internal::Eigensolver_statistics st;
    Eigen::VectorXd values;
    double t = best_time(repeats, [&] {
      smc::internal::laplace_beltrami_eigenpairs(lb.stiffness_matrix, lb.mass, im.component,
                                                 im.number_of_components, k, s, values, vectors, &st);
    });
    double error = 0;
    for(int j = 1; j < k; ++j) error = std::max(error, std::abs(values[j] - reference[j]) / reference[j]);
    report.add({std::to_string(ncv), sci(shift), sci(tolerance), Report::num(t, 4),
                std::to_string(st.restarts), std::to_string(st.operations), sci(error)});
  };
  for(int ncv : {120, 150, 201, 250, 300}) run(ncv, -1e-2, 1e-10);
  for(double shift : {-1.0, -1e-1, -1e-3, -1e-5}) run(201, shift, 1e-10);
  for(double tolerance : {1e-8, 1e-12}) run(201, -1e-2, tolerance);
  // Factorisation alone.
  Eigen::SparseMatrix<double> shifted = lb.stiffness_matrix;
  const double sigma = -1e-2 / lb.mass.sum();
  for(Eigen::Index i = 0; i < shifted.rows(); ++i) shifted.coeffRef(i, i) -= sigma * lb.mass[i];
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double> > ldlt;
  const double t_ldlt = best_time(repeats, [&] { ldlt.compute(shifted); });
  Eigen::VectorXd x = Eigen::VectorXd::Ones(shifted.rows()), y;
  const double t_solve = best_time(repeats, [&] { y = ldlt.solve(x); });
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double> > llt;
  const double t_llt = best_time(repeats, [&] { llt.compute(shifted); });
  report.print();
  Report per_k({"eigenpairs", "ncv", "seconds", "restarts", "solves"});
  for(int count : {30, 50, 100, 200})
  {
    smc::internal::Eigensolver_settings s;
    smc::internal::Eigensolver_statistics st;
    Eigen::VectorXd values;
    const double t = best_time(repeats, [&] {
      smc::internal::laplace_beltrami_eigenpairs(lb.stiffness_matrix, lb.mass, im.component,
                                                 im.number_of_components, count, s, values, vectors, &st);
    });
    per_k.add({std::to_string(count), std::to_string(st.krylov_dimension), Report::num(t, 4),
               std::to_string(st.restarts), std::to_string(st.operations)});
  }
  per_k.print();
  std::cout << "SimplicialLDLT factorisation " << t_ldlt << " s, one solve " << t_solve
            << " s; SimplicialLLT factorisation " << t_llt << " s\n";
}

void accuracy()
{
  Report report({"mesh", "vertices", "intrinsic_delaunay", "flips", "negative_weights",
                 "max_rel_error_l1_4", "mean_rel_error_l1_6", "seconds"});
  auto run = [&](const std::string& name, const smc_test::Mesh& mesh) {
    for(bool use_idt : {false, true})
    {
      Timer timer;
      const smc::Laplace_beltrami_spectrum s(
          mesh, params::use_intrinsic_delaunay(use_idt, params::number_of_eigenpairs(49)));
      const double seconds = timer.seconds();
      double max_error = 0, mean_error = 0;
      int j = 0, count = 0;
      for(int l = 0; l <= 6; ++l)
        for(int m = 0; m < 2 * l + 1; ++m, ++j)
          if(l > 0)
          {
            // On the unit sphere lambda = l (l + 1); rescale by the mesh area (slightly < 4 pi).
            const double lambda = s.eigenvalues()[j] * s.total_area() / (4 * smc_test::pi);
            const double e = std::abs(lambda - l * (l + 1)) / (l * (l + 1));
            if(l <= 4) max_error = std::max(max_error, e);
            mean_error += e;
            ++count;
          }
      report.add({name, std::to_string(s.number_of_vertices()), use_idt ? "yes" : "no",
                  std::to_string(s.number_of_flips()),
                  std::to_string(count_negative_weights(s.stiffness_matrix())),
                  Report::num(max_error, 4), Report::num(mean_error / count, 4),
                  Report::num(seconds, 3)});
    }
  };
  for(int level : {3, 4, 5}) run("icosphere", smc_test::icosphere(level));
  for(int level : {3, 4, 5}) run("jittered_0.45", smc_test::jittered_sphere(level, 0.45));
  for(int level : {3, 4, 5}) run("twisted_3", smc_test::twisted_sphere(level, 3.0));
  for(int level : {3, 4, 5}) run("twisted_6", smc_test::twisted_sphere(level, 6.0));
  report.print();
}

} // namespace

int main(int argc, char** argv)
{
  if(argc > 1 && std::strcmp(argv[1], "--sweep") == 0)
  {
    sweep(argc > 2 ? std::atoi(argv[2]) : 5000);
    return 0;
  }
  if(argc > 1 && std::strcmp(argv[1], "--accuracy") == 0)
  {
    accuracy();
    return 0;
  }
  std::vector<int> sizes;
  for(int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  if(sizes.empty()) sizes = {5000, 25000, 100000};
  timings(sizes);
  return 0;
}
