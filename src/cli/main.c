/* The ryushi command-line program (placeholder until the CLI lands). */
#include <stdio.h>

int main(void) {
    puts("ryushi " RY_VERSION);
    return 0;
}
