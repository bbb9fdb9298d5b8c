/* scene_keytab: the keys of a scene file, one table (scene_keytab.c): per
 * section its keys with type, unit, range, default and meaning.  The reader
 * (scene_keys.c) takes a section's keys, their ranges and its message for
 * an unknown key from it; scenes/README.md's key tables are generated from
 * it (`make doc-keys`, tests/scene_keys_table prints it). */
#ifndef SKINBAKE_SCENE_KEYTAB_H
#define SKINBAKE_SCENE_KEYTAB_H

enum scene_key_type {
	SCENE_KEY_TEXT,		/* any text */
	SCENE_KEY_NAME,		/* a name (letters, digits, _) */
	SCENE_KEY_PATH,		/* a file or directory, relative to the scene file */
	SCENE_KEY_NUMBER,	/* a decimal number in [lo, hi] */
	SCENE_KEY_INTEGER,	/* a whole number in [lo, hi] */
	SCENE_KEY_VECTOR,	/* three numbers x y z */
	SCENE_KEY_COLOUR,	/* three numbers r g b, each in [lo, hi] */
	SCENE_KEY_SWITCH,	/* on/off (yes/no, true/false, 1/0) */
	SCENE_KEY_CHOICE	/* one of `choices` */
};

struct scene_key {
	const char *section;	/* "scene", "camera", "light", "skin" or "object" */
	const char *name;
	enum scene_key_type type;
	const char *unit;	/* "" without one */
	double lo, hi;		/* NUMBER, INTEGER, COLOUR */
	const char *choices;	/* CHOICE: "a|b|c" */
	const char *def;	/* the default as the docs say it; "" for none or required */
	const char *doc;	/* what it does */
};

/* Every key, by section in the order [scene], [camera], [light], [skin],
 * [object]; ends with a row whose section is NULL. */
extern const struct scene_key scene_key_table[];

/* The key NAME of SECTION ("light" for [light NAME]), or NULL. */
const struct scene_key *scene_key_find(const char *section, const char *name);
/* SECTION's keys as "a, b, c" (static text, for messages). */
const char *scene_key_list(const char *section);
/* The type's word for the docs ("number", "on/off", ...). */
const char *scene_key_type_name(enum scene_key_type t);
#endif
