// the gransim command: everything lives in app/; this only hands over argc/argv
#include "app/cli.hpp"

int main(int argc, char** argv) { return gs::run_cli(argc, argv); }
