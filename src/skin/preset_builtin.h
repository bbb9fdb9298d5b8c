/* preset_builtin: the shipped presets as INI text (parsed by preset.c, so
 * built-in and user presets share one parser).  Sources of every value are
 * in the text's comments and in docs/presets.md. */
#ifndef SKINBAKE_PRESET_BUILTIN_H
#define SKINBAKE_PRESET_BUILTIN_H

struct builtin_preset {
	const char *name;	/* as given to --preset */
	const char *summary;	/* one line for `skinbake presets` */
	const char *ini;	/* preset INI text */
};

extern const struct builtin_preset builtin_presets[];
extern const int builtin_preset_count;
#endif
