#include <stdio.h>
int main(void) { puts("hamlie: under construction"); return 0; }
