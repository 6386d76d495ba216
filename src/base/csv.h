/* Line-based CSV text as the point files use it (sweep --init-file,
 * section --init-file): lines end at '\n'; blank lines and lines starting
 * with '#' are skipped; a line's fields end at ',' and are trimmed of
 * blanks (' ', '\t', '\r').  Everything is byte spans into the text, so
 * that an error can point at the field at fault.  (No quoting: the files
 * hold numbers and variable names.)
 *
 *   hl_csv c;
 *   int a, b;
 *   hl_csv_init(&c, text);
 *   while (hl_csv_line(&c, &a, &b))            // [a, b): a line with content
 *       for (int f = a, fa, fb; hl_csv_field(text, b, &f, &fa, &fb);)
 *           ...                                // [fa, fb): one field
 */
#ifndef HAMLIE_BASE_CSV_H
#define HAMLIE_BASE_CSV_H

typedef struct hl_csv {
    const char *text;
    int len, at; /* where the next line starts */
    int line;    /* the number (from 1) of the line last returned */
} hl_csv;

void hl_csv_init(hl_csv *c, const char *text);
/* The next line with content, trimmed, in [*a, *b); 0 at the end. */
int hl_csv_line(hl_csv *c, int *a, int *b);
/* The field of the line (ending at b) that starts at *f, trimmed, in
 * [*fa, *fb); *f moves past its comma.  0 once the line is done ("1,2,"
 * has three fields, the last empty). */
int hl_csv_field(const char *text, int b, int *f, int *fa, int *fb);
/* The index of the field [fa, fb) among names[0 .. n), or -1. */
int hl_csv_name(const char *text, int fa, int fb, const char *const *names, int n);

#endif
