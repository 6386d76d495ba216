/* Which code generator made a cache entry (jit_cache.c's key): the GNU
 * build-id of the object that holds hamlie's code (libhamlie.so, or the
 * executable it is linked into), so that any rebuild of it keys anew.
 * Apart from jit_cache.c because <link.h>'s <elf.h> and rules/rule.h both
 * define EV_NUM. */
#define _GNU_SOURCE
#include <link.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>

#include "tape/jit_cache_impl.h"

/* dl_iterate_phdr: the GNU build-id of the object that holds this code. */
typedef struct {
    uintptr_t addr;
    hl_buf *out;
    int found;
} build_id_search;

static int holds_addr(const struct dl_phdr_info *info, uintptr_t addr)
{
    for (int i = 0; i < info->dlpi_phnum; i++) {
        const ElfW(Phdr) *ph = &info->dlpi_phdr[i];
        uintptr_t lo = info->dlpi_addr + ph->p_vaddr;
        if (ph->p_type == PT_LOAD && addr >= lo && addr < lo + ph->p_memsz)
            return 1;
    }
    return 0;
}

static int note_build_id(const struct dl_phdr_info *info, hl_buf *out)
{
    for (int i = 0; i < info->dlpi_phnum; i++) {
        const ElfW(Phdr) *ph = &info->dlpi_phdr[i];
        if (ph->p_type != PT_NOTE)
            continue;
        const unsigned char *p = (const unsigned char *)(info->dlpi_addr + ph->p_vaddr);
        const unsigned char *end = p + ph->p_memsz;
        while (p + sizeof(ElfW(Nhdr)) <= end) {
            const ElfW(Nhdr) *n = (const ElfW(Nhdr) *)p;
            const unsigned char *name = p + sizeof *n;
            const unsigned char *desc = name + ((n->n_namesz + 3) & ~3u);
            if (n->n_type == NT_GNU_BUILD_ID && n->n_namesz == 4 && memcmp(name, "GNU", 4) == 0 &&
                desc + n->n_descsz <= end) {
                for (unsigned k = 0; k < n->n_descsz; k++)
                    hl_buf_printf(out, "%02x", desc[k]);
                return 1;
            }
            p = desc + ((n->n_descsz + 3) & ~3u);
        }
    }
    return 0;
}

static int find_build_id(struct dl_phdr_info *info, size_t size, void *data)
{
    (void)size;
    build_id_search *s = data;
    if (!holds_addr(info, s->addr))
        return 0;
    s->found = note_build_id(info, s->out);
    if (!s->found) { /* no build-id (another linker): the file's identity */
        struct stat st;
        const char *path = info->dlpi_name[0] ? info->dlpi_name : "/proc/self/exe";
        if (stat(path, &st) == 0)
            hl_buf_printf(s->out, "file %s %ld %lld %lld.%09ld", path, (long)st.st_ino,
                          (long long)st.st_size, (long long)st.st_mtim.tv_sec, st.st_mtim.tv_nsec);
    }
    return 1;
}

void hl_jit_generator_id(hl_buf *out)
{
    build_id_search s = {(uintptr_t)&hl_jit_generator_id, out, 0};
    dl_iterate_phdr(find_build_id, &s);
}
