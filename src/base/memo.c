/* Pointer -> value map for DAG walks (memo.h). */
#include <stdint.h>
#include <stdlib.h>

#include "base/buf.h"
#include "base/memo.h"

void hl_memo_init(hl_memo *m)
{
    m->cap = 64;
    m->count = 0;
    m->keys = hl_xcalloc(m->cap, sizeof *m->keys);
    m->vals = hl_xcalloc(m->cap, sizeof *m->vals);
}

void hl_memo_clear(hl_memo *m)
{
    free(m->keys);
    free(m->vals);
    m->keys = NULL;
    m->vals = NULL;
    m->cap = m->count = 0;
}

static size_t slot_of(const hl_memo *m, const void *key)
{
    size_t j = (size_t)(((uintptr_t)key >> 4) * 0x9e3779b97f4a7c15ULL) & (m->cap - 1);
    while (m->keys[j] != NULL && m->keys[j] != key)
        j = (j + 1) & (m->cap - 1);
    return j;
}

hl_memo_val *hl_memo_get(const hl_memo *m, const void *key)
{
    size_t j = slot_of(m, key);
    return m->keys[j] == key ? &m->vals[j] : NULL;
}

static void grow(hl_memo *m)
{
    hl_memo old = *m;
    m->cap *= 2;
    m->count = 0;
    m->keys = hl_xcalloc(m->cap, sizeof *m->keys);
    m->vals = hl_xcalloc(m->cap, sizeof *m->vals);
    for (size_t i = 0; i < old.cap; i++)
        if (old.keys[i] != NULL) {
            size_t j = slot_of(m, old.keys[i]);
            m->keys[j] = old.keys[i];
            m->vals[j] = old.vals[i];
            m->count++;
        }
    hl_memo_clear(&old);
}

hl_memo_val *hl_memo_put(hl_memo *m, const void *key)
{
    if (2 * (m->count + 1) > m->cap)
        grow(m);
    size_t j = slot_of(m, key);
    if (m->keys[j] == NULL) {
        m->keys[j] = key;
        m->count++;
    }
    return &m->vals[j];
}
