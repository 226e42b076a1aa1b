// Streams a CSV of raw inputs through a tpf weight file with the core engine (double), for the
// PyTorch parity test: tcn_stream <weights.json> <inputs.csv> <outputs.csv>.
// inputs.csv: T rows of In comma-separated values; outputs.csv: T rows [low…, high…] after
// reset(first row), one step per row. Prints the median step time [µs] on stdout.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "tpf/common/error.hpp"
#include "tpf/nn/load_tcn_weights.hpp"
#include "tpf/nn/tcn.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace {

std::vector<std::vector<double>> read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw tpf::Error::at(path, 0, "file", "cannot open");
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ','))
      row.push_back(std::stod(cell));
    rows.push_back(std::move(row));
  }
  return rows;
}

template <int In, int Hidden, int Out>
void stream(const std::string& weights, const std::vector<std::vector<double>>& rows,
            const std::string& out_path) {
  using Network = tpf::Tcn<double, In, Hidden, 4, 4, Out>;
  auto tcn = std::make_unique<Network>();
  tpf::load_tcn_weights(weights, *tcn);
  const auto input = [&](std::size_t t) {
    if (rows[t].size() != In) throw tpf::Error::at("inputs", t + 1, "columns", "wrong count");
    return typename Network::Input(Eigen::Map<const Eigen::Matrix<double, In, 1>>(rows[t].data()));
  };
  std::ofstream out(out_path);
  out.precision(17);
  std::vector<double> micros;
  tcn->reset(input(0));
  for (std::size_t t = 0; t < rows.size(); ++t) {
    const auto x = input(t);
    const auto start = std::chrono::steady_clock::now();
    tcn->step(x);
    micros.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
            .count());
    for (int o = 0; o < Out; ++o)
      out << tcn->low()[o] << ',';
    for (int o = 0; o < Out; ++o)
      out << tcn->high()[o] << (o + 1 < Out ? "," : "\n");
  }
  std::nth_element(micros.begin(), micros.begin() + micros.size() / 2, micros.end());
  std::printf("%.4f\n", micros[micros.size() / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: tcn_stream <weights.json> <inputs.csv> <outputs.csv>\n";
    return 2;
  }
  try {
    const tpf::TcnWeightFile file = tpf::read_tcn_weight_file(argv[1]);
    const auto rows = read_csv(argv[2]);
    if (rows.empty()) throw tpf::Error::at(argv[2], 0, "rows", "no input rows");
    if (file.levels != 4 || file.kernel != 4)
      throw tpf::Error::at(argv[1], 0, "architecture", "this tool is compiled for 4 levels, K = 4");
    if (file.inputs == 4 && file.hidden == 16 && file.outputs == 1)
      stream<4, 16, 1>(argv[1], rows, argv[3]);
    else if (file.inputs == 4 && file.hidden == 32 && file.outputs == 1)
      stream<4, 32, 1>(argv[1], rows, argv[3]);
    else if (file.inputs == 16 && file.hidden == 32 && file.outputs == 4)
      stream<16, 32, 4>(argv[1], rows, argv[3]);
    else
      throw tpf::Error::at(argv[1], 0, "architecture",
                           "compiled for 4→16→1, 4→32→1 and 16→32→4 only");
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
