// gransim's entry point
#include "app/cli.hpp"

int main(int argc, char** argv) { return gs::run_cli(argc, argv); }
