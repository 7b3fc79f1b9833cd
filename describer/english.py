"""English morphology the describer needs: plurals, articles, number words, lists.

Thin wrappers around ``inflect`` so the rest of the describer never builds an English
word form by hand. A catalog's irregular plural ("sacks of flour") always wins over
inflection. inflect's plural takes time quadratic in the length of what it is given,
so a noun phrase longer than ``MAX_INFLECTED_CHARS`` (only a hand-made scene.json has
one: the rules checker refuses nouns that long) has only its last word inflected.
"""

from __future__ import annotations

import importlib
import sys
import types
from functools import lru_cache


def _import_inflect():
    """Import inflect without typeguard's import-time instrumentation.

    inflect 7 wraps its API in ``typeguard.typechecked``, which re-compiles each function
    when the module is imported: about 2 s here, most of a ``generate`` run's start-up
    (jaraco/inflect#212). We call inflect only with the types it declares, so it is
    imported while ``typechecked`` is the identity, which typeguard itself does under
    ``python -O``. Where typeguard is not imported yet, inflect meets a stand-in that
    holds only that identity (the one name inflect imports from it): importing typeguard
    itself pulls in unittest.mock and asyncio, a noticeable part of the start-up.
    """
    if "inflect" in sys.modules:
        return sys.modules["inflect"]

    def identity(function=None, **_):
        return function if function else (lambda f: f)

    real = sys.modules.get("typeguard")
    if real is None:
        stand_in = types.ModuleType("typeguard")
        stand_in.typechecked = identity
        sys.modules["typeguard"] = stand_in
        try:
            return importlib.import_module("inflect")
        finally:
            del sys.modules["typeguard"]
    original = real.typechecked
    real.typechecked = identity
    try:
        return importlib.import_module("inflect")
    finally:
        real.typechecked = original


_ENGINE = _import_inflect().engine()


#: The longest noun phrase given to inflect whole, in characters (the rules checker's
#: limit on a noun's length).
MAX_INFLECTED_CHARS = 200

#: The word forms below are pure functions of their arguments, kept once computed: a
#: dataset asks for the same few catalog nouns and numbers thousands of times, and
#: each of inflect's answers runs dozens of regular expressions.
_remembered = lru_cache(maxsize=4096)


@_remembered
def plural_of(noun: str, irregular: str | None = None) -> str:
    """The plural of a noun phrase: the catalog's irregular form when it has one.

    A phrase longer than ``MAX_INFLECTED_CHARS`` keeps all but its last word as it is;
    a last word that long alone gets an "s".
    """
    if irregular:
        return irregular
    if len(noun) <= MAX_INFLECTED_CHARS:
        return _ENGINE.plural_noun(noun)
    rest, space, last = noun.rpartition(" ")
    if len(last) > MAX_INFLECTED_CHARS:
        return noun + "s"
    return rest + space + _ENGINE.plural_noun(last)


#: Endings of words that look plural but are not ("class", "physics", "lens"), which
#: inflect's singular_noun would cut.
_NOT_PLURAL_ENDINGS = ("ss", "us", "is", "ics", "news", "series", "species", "lens")


def singular_of(name: str) -> str:
    """A name whose last word is a plural noun, made singular ("bedrooms" -> "bedroom",
    "dining rooms" -> "dining room"); any other name as it is. Cautious: only a form
    whose plural gives the word back and that does not end in a vowel inflect guessed
    ("campus" is not "campu"), and never a word with an ending in ``_NOT_PLURAL_ENDINGS``."""
    rest, space, last = name.rpartition(" ")
    word = last.lower()
    if (
        not word.endswith("s")
        or word.endswith(_NOT_PLURAL_ENDINGS)
        or len(word) > MAX_INFLECTED_CHARS
    ):
        return name
    one = _ENGINE.singular_noun(word)
    if not one or one[-1] in "aiu" or _ENGINE.plural_noun(one) != word:
        return name
    return rest + space + one


@_remembered
def with_article(noun: str) -> str:
    """The noun phrase with "a" or "an" in front ("an oak tree", "a big pot of stew")."""
    return _ENGINE.a(noun)


@_remembered
def number_word(count: int) -> str:
    """A count as a word ("three", "twenty-one")."""
    return _ENGINE.number_to_words(count)


@_remembered
def ordinal_word(position: int) -> str:
    """A 1-based position as an ordinal word ("first", "twenty-second")."""
    return _ENGINE.number_to_words(_ENGINE.ordinal(position))


def counted(count: int, noun: str, plural: str) -> str:
    """An indefinite noun phrase for ``count`` things: "an oak tree", "three roads"."""
    return with_article(noun) if count == 1 else f"{number_word(count)} {plural}"


def join_list(items: list[str]) -> str:
    """Items joined as English lists them: "a", "a and b", "a, b and c"."""
    if not items:
        return ""
    if len(items) == 1:
        return items[0]
    return ", ".join(items[:-1]) + " and " + items[-1]


@_remembered
def verb_agreeing(verb_phrase: str, plural: bool) -> str:
    """A verb phrase written in the third person singular, made to agree with its subject.

    Only the first word is the finite verb ("is next to" -> "are next to", "faces away
    from" -> "face away from").
    """
    if not plural:
        return verb_phrase
    verb, _, rest = verb_phrase.partition(" ")
    agreed = _ENGINE.plural_verb(verb)
    return f"{agreed} {rest}" if rest else agreed


def without_repeated_copula(predicates: list[str]) -> list[str]:
    """Coordinated predicates with "is" / "are" said once: "is next to the road and (is) north of the well"."""
    copula = predicates[0].split(" ", 1)[0] if predicates else ""
    if copula not in ("is", "are"):
        return list(predicates)
    rest = [p.removeprefix(copula + " ") for p in predicates[1:]]
    return predicates[:1] + rest


def with_also(predicate: str) -> str:
    """The predicate with "also" where English puts it: "is also next to", "also faces"."""
    verb, _, rest = predicate.partition(" ")
    return f"{verb} also {rest}" if verb in ("is", "are") else f"also {predicate}"


def sentence_case(text: str) -> str:
    """The text with its first letter capitalised (the rest untouched)."""
    return text[:1].upper() + text[1:]
