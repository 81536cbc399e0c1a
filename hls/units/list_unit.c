/* Mailboxed list unit: see list_unit.h. */
#include "list_unit.h"

#include "trace_ops.h"

static void mailbox_clear(trace_mailbox *m)
{
mailbox_clear_loop:
    for (int i = 0; i < TRACE_MAILBOX; i++)
        m->key[i] = TRACE_NO_HIT;
    m->next = 0;
}

/* 1 if key was seen (skip it), else remembers it (round robin) and returns 0. */
static int mailbox_seen(trace_mailbox *m, uint32_t key)
{
mailbox_search:
    for (int i = 0; i < TRACE_MAILBOX; i++)
        if (m->key[i] == key)
            return 1;
    m->key[m->next] = key;
    m->next = (m->next + 1) % TRACE_MAILBOX;
    return 0;
}

void list_mailboxes_clear(trace_mailbox box[TRACE_PACKET])
{
mailbox_clear_rays:
    for (int i = 0; i < TRACE_PACKET; i++)
        mailbox_clear(&box[i]);
}

uint32_t list_unit_entry(const uint32_t *mem, trav_walker *w, trace_mailbox box[TRACE_PACKET], uint32_t alive,
                         uint32_t *key, unit_op *op, trace_counters *c)
{
    const uint32_t a = w->lists + w->leaf_first + w->k, entry = mem[a];
    uint32_t need = 0;
    *key = entry;
    op_set(op, OP_LIST, 1);
    op_read(op, c, MEM_LISTS, a, 1);
    c->list_entries++;
    w->k++;
mailbox_rays:
    for (int i = 0; i < TRACE_PACKET; i++) {
        if (!bit(w->leaf_mask & alive, i))
            continue;
        if (mailbox_seen(&box[i], entry))
            c->mailbox_skips++;
        else
            need |= 1u << i;
    }
    return need;
}
