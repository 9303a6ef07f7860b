/* scene_json: a small strict JSON parser (RFC 8259) that records the line of
 * every value and object key, so scene-file errors can name file:line.
 * cJSON keeps no positions, hence this parser. Used by the scene module and
 * by the perf.json reader of `meadow bench --perf` (src/perf/perf.c).
 * Rejects: trailing garbage, trailing commas, comments, duplicate keys,
 * control characters in strings, \u0000, lone surrogates, non-finite numbers,
 * nesting deeper than SCENE_JSON_MAX_DEPTH. */
#ifndef MEADOW_SCENE_JSON_H
#define MEADOW_SCENE_JSON_H

#include <stdbool.h>
#include <stddef.h>

#define SCENE_JSON_MAX_DEPTH 64

typedef enum scene_json_type_t {
    SCENE_JSON_NULL,
    SCENE_JSON_BOOL,
    SCENE_JSON_NUMBER,
    SCENE_JSON_STRING,
    SCENE_JSON_ARRAY,
    SCENE_JSON_OBJECT,
} scene_json_type_t;

typedef struct scene_json_t {
    scene_json_type_t type;
    int line;                   /* 1-based line where the value starts */
    const char *key;            /* member name inside an object, else NULL */
    int key_line;               /* line of the key */
    bool boolean;
    double number;
    const char *string;         /* decoded UTF-8, NUL-terminated */
    size_t string_len;
    struct scene_json_t *child; /* first element / member */
    struct scene_json_t *next;  /* next sibling */
    int count;                  /* number of children */
} scene_json_t;

typedef struct scene_json_doc_t {
    scene_json_t *root;
    void *arena; /* all nodes and strings; freed by scene_json_free */
} scene_json_doc_t;

/* Parses NUL-terminated text. On failure writes "name:line: message" into err
 * and returns false (doc is left empty). */
bool scene_json_parse(scene_json_doc_t *doc, const char *text, const char *name, char *err,
                      size_t err_size);
void scene_json_free(scene_json_doc_t *doc);
/* Member of an object by key, or NULL. */
const scene_json_t *scene_json_get(const scene_json_t *obj, const char *key);
/* "null", "boolean", "number", "string", "array", "object". */
const char *scene_json_type_name(scene_json_type_t type);

#endif
