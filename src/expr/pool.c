/* The expression pool: owns every node and hash-conses them, so that
 * structurally equal expressions are the same pointer. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/expr.h"

/* Nodes are allocated in chunks and never moved, so pointers stay valid. */
#define CHUNK_NODES 1024

typedef struct chunk {
    struct chunk *next;
    size_t used;
    hl_expr nodes[CHUNK_NODES];
} chunk;

typedef struct name_entry {
    struct name_entry *next;
    char name[]; /* interned symbol name */
} name_entry;

struct hl_pool {
    chunk *chunks;
    unsigned count;       /* nodes made so far: the next id */
    const hl_expr **slot; /* open-addressing hash table of nodes */
    size_t nslots;        /* a power of two */
    name_entry *names;
};

static const char *const fun_names[HL_FUN_COUNT] = {
    "sin", "cos", "tan", "exp", "log", "sqrt",
    "atan", "asin", "acos", "sinh", "cosh", "tanh", "atan2", "asinh",
};

const char *hl_fun_name(hl_fun f)
{
    return (unsigned)f < HL_FUN_COUNT ? fun_names[f] : "?";
}

int hl_fun_arity(hl_fun f)
{
    return f == HL_ATAN2 ? 2 : 1;
}

int hl_fun_lookup(const char *name, int len)
{
    for (int f = 0; f < HL_FUN_COUNT; f++)
        if ((int)strlen(fun_names[f]) == len && memcmp(fun_names[f], name, (size_t)len) == 0)
            return f;
    return -1;
}

hl_pool *hl_pool_new(void)
{
    hl_pool *pool = hl_xcalloc(1, sizeof *pool);
    pool->nslots = 1024;
    pool->slot = hl_xcalloc(pool->nslots, sizeof *pool->slot);
    return pool;
}

void hl_pool_free(hl_pool *pool)
{
    if (pool == NULL)
        return;
    for (chunk *c = pool->chunks; c != NULL;) {
        chunk *next = c->next;
        for (size_t i = 0; i < c->used; i++)
            if (c->nodes[i].kind == HL_NUM)
                fmpq_clear(c->nodes[i].num);
        free(c);
        c = next;
    }
    for (name_entry *e = pool->names; e != NULL;) {
        name_entry *next = e->next;
        free(e);
        e = next;
    }
    free(pool->slot);
    free(pool);
}

/* ---- hashing and equality of a candidate node ---------------------------- */

static unsigned long mix(unsigned long h, unsigned long v)
{
    h ^= v + 0x9e3779b97f4a7c15UL + (h << 6) + (h >> 2);
    return h;
}

static unsigned long node_hash(const hl_expr *n)
{
    unsigned long h = mix(0, (unsigned long)n->kind);
    switch (n->kind) {
    case HL_NUM:
        h = mix(h, (unsigned long)fmpz_get_si(fmpq_numref(n->num)));
        h = mix(h, (unsigned long)fmpz_get_si(fmpq_denref(n->num)));
        h = mix(h, (unsigned long)fmpz_size(fmpq_numref(n->num)));
        break;
    case HL_SYM:
        h = mix(h, (unsigned long)(uintptr_t)n->name); /* names are interned */
        break;
    case HL_PI:
        break;
    case HL_FUN:
        h = mix(h, (unsigned long)n->fun);
        /* fall through */
    default:
        h = mix(h, n->a ? n->a->hash : 0);
        h = mix(h, n->b ? n->b->hash : 0);
    }
    return h;
}

static int node_equal(const hl_expr *x, const hl_expr *y)
{
    if (x->kind != y->kind || x->hash != y->hash)
        return 0;
    switch (x->kind) {
    case HL_NUM: return fmpq_equal(x->num, y->num);
    case HL_SYM: return x->name == y->name;
    case HL_PI: return 1;
    case HL_FUN: return x->fun == y->fun && x->a == y->a && x->b == y->b;
    default: return x->a == y->a && x->b == y->b;
    }
}

/* ---- the table ----------------------------------------------------------- */

/* The slot of a hash: node_hash's combination leaves its low bits poorly
 * spread (Lie series of order 100 probed ~10^3 slots a lookup), so they
 * are mixed first (MurmurHash3's 64-bit finaliser). */
static size_t home_slot(unsigned long h, size_t nslots)
{
    uint64_t x = h;
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdULL;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ULL;
    x ^= x >> 33;
    return (size_t)x & (nslots - 1);
}

static void grow(hl_pool *pool)
{
    size_t n = pool->nslots * 2;
    const hl_expr **slot = hl_xcalloc(n, sizeof *slot);
    for (size_t i = 0; i < pool->nslots; i++) {
        const hl_expr *e = pool->slot[i];
        if (e == NULL)
            continue;
        size_t j = home_slot(e->hash, n);
        while (slot[j] != NULL)
            j = (j + 1) & (n - 1);
        slot[j] = e;
    }
    free(pool->slot);
    pool->slot = slot;
    pool->nslots = n;
}

static hl_expr *new_node(hl_pool *pool)
{
    if (pool->chunks == NULL || pool->chunks->used == CHUNK_NODES) {
        chunk *c = hl_xmalloc(sizeof *c);
        c->next = pool->chunks;
        c->used = 0;
        pool->chunks = c;
    }
    hl_expr *n = &pool->chunks->nodes[pool->chunks->used++];
    memset(n, 0, sizeof *n);
    return n;
}

/* Return the pooled node equal to the candidate, adding it if new.  The
 * candidate's fmpq (if any) is copied, never adopted. */
static const hl_expr *intern(hl_pool *pool, hl_expr *cand)
{
    cand->hash = node_hash(cand);
    if (2 * (pool->count + 1) > pool->nslots)
        grow(pool);
    size_t j = home_slot(cand->hash, pool->nslots);
    for (; pool->slot[j] != NULL; j = (j + 1) & (pool->nslots - 1))
        if (node_equal(pool->slot[j], cand))
            return pool->slot[j];
    hl_expr *n = new_node(pool);
    n->kind = cand->kind;
    n->fun = cand->fun;
    n->hash = cand->hash;
    n->name = cand->name;
    n->a = cand->a;
    n->b = cand->b;
    if (cand->kind == HL_NUM) {
        fmpq_init(n->num);
        fmpq_set(n->num, cand->num);
    }
    n->id = pool->count++;
    pool->slot[j] = n;
    return n;
}

static const char *intern_name(hl_pool *pool, const char *name)
{
    for (name_entry *e = pool->names; e != NULL; e = e->next)
        if (strcmp(e->name, name) == 0)
            return e->name;
    size_t len = strlen(name) + 1;
    name_entry *e = hl_xmalloc(sizeof *e + len);
    memcpy(e->name, name, len);
    e->next = pool->names;
    pool->names = e;
    return e->name;
}

/* ---- constructors ---------------------------------------------------------- */

const hl_expr *hl_num_fmpq(hl_pool *pool, const fmpq_t x)
{
    hl_expr cand;
    memset(&cand, 0, sizeof cand);
    cand.kind = HL_NUM;
    *cand.num = *x; /* shallow view: intern copies it */
    return intern(pool, &cand);
}

const hl_expr *hl_num_si(hl_pool *pool, long n)
{
    fmpq_t x;
    fmpq_init(x);
    fmpq_set_si(x, n, 1);
    const hl_expr *e = hl_num_fmpq(pool, x);
    fmpq_clear(x);
    return e;
}

const hl_expr *hl_num_frac(hl_pool *pool, long p, unsigned long q)
{
    fmpq_t x;
    fmpq_init(x);
    fmpz_set_si(fmpq_numref(x), p);
    fmpz_set_ui(fmpq_denref(x), q ? q : 1);
    fmpq_canonicalise(x);
    const hl_expr *e = hl_num_fmpq(pool, x);
    fmpq_clear(x);
    return e;
}

const hl_expr *hl_sym(hl_pool *pool, const char *name)
{
    hl_expr cand;
    memset(&cand, 0, sizeof cand);
    cand.kind = HL_SYM;
    cand.name = intern_name(pool, name);
    return intern(pool, &cand);
}

const hl_expr *hl_pi(hl_pool *pool)
{
    hl_expr cand;
    memset(&cand, 0, sizeof cand);
    cand.kind = HL_PI;
    return intern(pool, &cand);
}

static const hl_expr *make(hl_pool *pool, hl_expr_kind kind, hl_fun fun, const hl_expr *a,
                           const hl_expr *b)
{
    hl_expr cand;
    memset(&cand, 0, sizeof cand);
    cand.kind = kind;
    cand.fun = fun;
    cand.a = a;
    cand.b = b;
    return intern(pool, &cand);
}

const hl_expr *hl_neg(hl_pool *pool, const hl_expr *a) { return make(pool, HL_NEG, 0, a, NULL); }
const hl_expr *hl_add(hl_pool *pool, const hl_expr *a, const hl_expr *b) { return make(pool, HL_ADD, 0, a, b); }
const hl_expr *hl_sub(hl_pool *pool, const hl_expr *a, const hl_expr *b) { return make(pool, HL_SUB, 0, a, b); }
const hl_expr *hl_mul(hl_pool *pool, const hl_expr *a, const hl_expr *b) { return make(pool, HL_MUL, 0, a, b); }
const hl_expr *hl_div(hl_pool *pool, const hl_expr *a, const hl_expr *b) { return make(pool, HL_DIV, 0, a, b); }
const hl_expr *hl_pow(hl_pool *pool, const hl_expr *a, const hl_expr *b) { return make(pool, HL_POW, 0, a, b); }
const hl_expr *hl_call(hl_pool *pool, hl_fun f, const hl_expr *a) { return make(pool, HL_FUN, f, a, NULL); }
const hl_expr *hl_call2(hl_pool *pool, hl_fun f, const hl_expr *a, const hl_expr *b) { return make(pool, HL_FUN, f, a, b); }
