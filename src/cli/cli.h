/* Sub-commands of the ryushi program, one file each. */
#ifndef RYUSHI_CLI_H
#define RYUSHI_CLI_H

int ry_cli_bench(int argc, char **argv);
int ry_cli_plot(int argc, char **argv);
int ry_cli_validate(int argc, char **argv);

#endif
