/*
 * Shared edges of an object's triangles (docs/memory-image.md, "Triangle records"): the edges a
 * triangle has in common with another triangle of the object that is not its coincident copy.
 * The intersection unit widens its barycentric bounds on these edges only (isect_unit.h), which
 * closes the cracks fp24's independent roundings open between two neighbours without moving a
 * silhouette. Vertices are welded by position, not by index: meshes often repeat a vertex per
 * face for its normal or texture coordinates.
 */
#include "huge_pages.h"
#include "memimage.h"

#include <stdlib.h>
#include <string.h>

/* The ends of edge k (its opposite vertex is k): edge 0 is B C where u = 0, edge 1 A C where
 * v = 0, edge 2 A B where u + v = 1, in the order of the TRI_SHARED_* bits. */
static const int edge_end[3][2] = { { 1, 2 }, { 0, 2 }, { 0, 1 } };

typedef struct {
    const scene_mesh *m;
    const uint32_t *tri;
} edge_source;

static const float *corner(const edge_source *s, uint32_t e, int k)
{
    return &s->m->positions[3 * (size_t)s->m->indices[3 * (size_t)s->tri[e / 3] + (size_t)k]];
}

/* Positions compare by value (+0 equals -0). */
static int same_point(const float *a, const float *b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

static int point_less(const float *a, const float *b)
{
    return a[0] != b[0] ? a[0] < b[0] : a[1] != b[1] ? a[1] < b[1] : a[2] < b[2];
}

/* The ends of edge e, the smaller position first, so that both triangles see the same pair. */
static void edge_ends(const edge_source *s, uint32_t e, const float *p[2])
{
    const float *a = corner(s, e, edge_end[e % 3][0]), *b = corner(s, e, edge_end[e % 3][1]);
    const int swap = point_less(b, a);
    p[0] = swap ? b : a;
    p[1] = swap ? a : b;
}

static uint64_t hash_point(uint64_t h, const float *p)
{
    for (int k = 0; k < 3; k++) {
        const float x = p[k] + 0.0f; /* -0 + 0 = +0: equal positions hash alike */
        uint32_t bits;
        memcpy(&bits, &x, sizeof bits);
        h = (h ^ bits) * 0x9E3779B97F4A7C15ull;
        h ^= h >> 29;
    }
    return h;
}

static uint64_t hash_edge(const edge_source *s, uint32_t e)
{
    const float *p[2];
    edge_ends(s, e, p);
    return hash_point(hash_point(0x243F6A8885A308D3ull, p[0]), p[1]);
}

/* Edges e and f join the same two positions, and their triangles are not coincident copies (a
 * double-sided surface's back face shares its outline, which stays a silhouette). */
static int shared_with(const edge_source *s, uint32_t e, uint32_t f)
{
    const float *p[2], *q[2];
    edge_ends(s, e, p);
    edge_ends(s, f, q);
    return same_point(p[0], q[0]) && same_point(p[1], q[1]) &&
           !same_point(corner(s, e, (int)(e % 3)), corner(s, f, (int)(f % 3)));
}

/* One pass: every edge is inserted at the first free slot of its probe sequence, after the
 * edges with its position pair that came before it, so it meets each of them on the way. A slot
 * holds the edge and the high half of its hash: equal position pairs hash alike, so only edges
 * with the same tag can be shared, and the others are passed without reading their triangles'
 * positions (scattered loads, most of the time this took). */
/* t's slots, at least size of them, all empty: its block if that is large enough, else a new one
 * (the old freed). A block reused between objects is one the kernel need not zero again: the
 * gallery's seven tables were 30 MB of fresh pages, its largest is 8 MB. NULL: out of memory. */
static uint64_t *table_slots(mi_edge_table *t, size_t size)
{
    if (t->size < size) {
        free(t->slot);
        t->size = 0;
        /* huge pages: the gallery's tables are 2-8 MB */
        if (!(t->slot = huge_pages_malloc(size * sizeof *t->slot)))
            return NULL;
        t->size = size;
    }
    memset(t->slot, 0xFF, size * sizeof *t->slot); /* empty: edge UINT32_MAX, never one of the 3 n */
    return t->slot;
}

void mi_edge_table_free(mi_edge_table *t)
{
    free(t->slot);
    t->slot = NULL;
    t->size = 0;
}

int mi_shared_edges(const scene_mesh *m, const uint32_t *tri, uint32_t n, uint8_t *flags, mi_edge_table *t)
{
    const edge_source s = { m, tri };
    const uint32_t edges = 3 * n;
    size_t size = 2;
    while (size < 2 * (size_t)edges)
        size *= 2;
    /* open addressing, linear probing, load <= 1/2 */
    mi_edge_table own = { 0 }, *table = t ? t : &own;
    uint64_t *slot = table_slots(table, size);
    if (!slot)
        return -1;
    memset(flags, 0, n);
    for (uint32_t e = 0; e < edges; e++) {
        const uint64_t h = hash_edge(&s, e), tag = h & 0xFFFFFFFF00000000ull;
        size_t i = (size_t)h & (size - 1);
        for (; (uint32_t)slot[i] != UINT32_MAX; i = (i + 1) & (size - 1)) {
            const uint32_t f = (uint32_t)slot[i];
            if ((slot[i] & 0xFFFFFFFF00000000ull) == tag && shared_with(&s, e, f)) {
                flags[e / 3] |= (uint8_t)(1u << (e % 3));
                flags[f / 3] |= (uint8_t)(1u << (f % 3));
            }
        }
        slot[i] = tag | e;
    }
    mi_edge_table_free(&own);
    return 0;
}
