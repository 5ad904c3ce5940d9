// cable_sim: offline cable solver. All logic lives in cli_app.cpp.
#include <iostream>

#include "cli_app.hpp"

int main(int argc, char** argv) {
  return mooring_dynamics::cli::runCli(argc, argv, std::cout, std::cerr);
}
