"""What people call AI2-THOR objects: phrase -> object type.

Every type's own name, split at its capitals ("CounterTop" -> "counter top", "countertop"), is a phrase
automatically; the table below adds the synonyms, abbreviations and misspellings found in ALFRED's
human annotations. Ambiguous words ("lamp", "light", "table", "bottle") map to a tuple of candidates
that the parser narrows down with the room type.
"""

from __future__ import annotations

import re

SYNONYMS: dict[str, str | tuple[str, ...]] = {
    # appliances and fixtures
    "fridge": "Fridge", "refrigerator": "Fridge", "refridgerator": "Fridge", "refrigirator": "Fridge",
    "freezer": "Fridge", "icebox": "Fridge", "frige": "Fridge", "fride": "Fridge",
    "microwave": "Microwave", "microwave oven": "Microwave", "oven": "Microwave", "mircowave": "Microwave",
    "microwve": "Microwave", "micro wave": "Microwave",
    "stove": "StoveBurner", "stove top": "StoveBurner", "stovetop": "StoveBurner", "burner": "StoveBurner",
    "range": "StoveBurner", "cooktop": "StoveBurner",
    "sink": "SinkBasin", "basin": "SinkBasin", "kitchen sink": "SinkBasin", "bathroom sink": "SinkBasin",
    "tub": "BathtubBasin", "bathtub": "BathtubBasin", "bath tub": "BathtubBasin", "bath": "BathtubBasin",
    "toilet": "Toilet", "commode": "Toilet", "toilet tank": "Toilet", "toilet basin": "Toilet",
    "toilet paper holder": "ToiletPaperHanger", "toilet paper hanger": "ToiletPaperHanger",
    "toilet roll holder": "ToiletPaperHanger", "paper holder": "ToiletPaperHanger", "holder": "ToiletPaperHanger",
    "toilet paper roll holder": "ToiletPaperHanger", "roll holder": "ToiletPaperHanger",
    "coffee maker": "CoffeeMachine", "coffee machine": "CoffeeMachine", "coffeemaker": "CoffeeMachine",
    "coffee pot": "CoffeeMachine", "espresso machine": "CoffeeMachine",
    "trash": "GarbageCan", "trash can": "GarbageCan", "trashcan": "GarbageCan", "garbage": "GarbageCan",
    "garbage can": "GarbageCan", "garbage bin": "GarbageCan", "bin": "GarbageCan", "trash bin": "GarbageCan",
    "wastebasket": "GarbageCan", "waste basket": "GarbageCan", "recycling bin": "GarbageCan",
    "rubbish bin": "GarbageCan", "waste bin": "GarbageCan", "trashbin": "GarbageCan",
    # furniture
    "counter": "CounterTop", "counters": "CounterTop", "kitchen counter": "CounterTop", "worktop": "CounterTop",
    "kitchen island": "CounterTop", "island": "CounterTop", "countertop": "CounterTop",
    "table": ("DiningTable", "SideTable", "CoffeeTable"), "stand": "SideTable", "kitchen table": "DiningTable", "dinner table": "DiningTable",
    "dining room table": "DiningTable", "round table": "DiningTable", "white table": "DiningTable",
    "coffee table": "CoffeeTable", "glass table": "CoffeeTable", "ottoman table": "CoffeeTable",
    "side table": "SideTable", "end table": "SideTable", "nightstand": "SideTable", "night stand": "SideTable",
    "bedside table": "SideTable", "night table": "SideTable",
    "desk": "Desk", "work desk": "Desk", "computer desk": "Desk",
    "shelf": "Shelf", "shelves": "Shelf", "shelving": "Shelf", "bookshelf": "Shelf", "book shelf": "Shelf",
    "cabinet": "Cabinet", "cupboard": "Cabinet", "cabinets": "Cabinet", "cupboards": "Cabinet",
    "drawer": "Drawer", "drawers": "Drawer",
    "dresser": "Dresser", "chest of drawers": "Dresser", "bureau": "Dresser", "tv stand": "Dresser",
    "bed": "Bed", "mattress": "Bed",
    "sofa": "Sofa", "couch": "Sofa", "loveseat": "Sofa", "love seat": "Sofa", "settee": "Sofa",
    "armchair": "ArmChair", "arm chair": "ArmChair", "chair": "ArmChair", "recliner": "ArmChair",
    "lounge chair": "ArmChair", "easy chair": "ArmChair",
    "ottoman": "Ottoman", "footstool": "Ottoman", "foot stool": "Ottoman", "foot rest": "Ottoman",
    "safe": "Safe", "cart": "Cart", "trolley": "Cart",
    # lamps: ambiguous without the room
    "lamp": ("DeskLamp", "FloorLamp"), "light": ("DeskLamp", "FloorLamp"), "lights": ("DeskLamp", "FloorLamp"),
    "light source": ("DeskLamp", "FloorLamp"),
    "desk lamp": "DeskLamp", "table lamp": "DeskLamp", "bedside lamp": "DeskLamp", "reading lamp": "DeskLamp",
    "floor lamp": "FloorLamp", "standing lamp": "FloorLamp", "tall lamp": "FloorLamp", "floorlamp": "FloorLamp",
    # things people pick up
    "mug": "Mug", "coffee mug": "Mug", "coffee cup": "Mug", "tea cup": "Cup", "cup": "Cup", "glass": "Cup",
    "remote": "RemoteControl", "remote control": "RemoteControl", "controller": "RemoteControl",
    "tv remote": "RemoteControl", "television remote": "RemoteControl", "clicker": "RemoteControl",
    "phone": "CellPhone", "cell phone": "CellPhone", "cellphone": "CellPhone", "smartphone": "CellPhone",
    "smart phone": "CellPhone", "mobile phone": "CellPhone", "mobile": "CellPhone", "telephone": "CellPhone",
    "keys": "KeyChain", "key": "KeyChain", "key chain": "KeyChain", "keychain": "KeyChain",
    "key ring": "KeyChain", "set of keys": "KeyChain", "keyring": "KeyChain",
    "card": "CreditCard", "credit card": "CreditCard", "debit card": "CreditCard", "creditcard": "CreditCard",
    "cd": "CD", "disc": "CD", "disk": "CD", "dvd": "CD", "compact disc": "CD", "cd case": "CD",
    "laptop": "Laptop", "computer": "Laptop", "lap top": "Laptop", "notebook computer": "Laptop",
    "book": "Book", "novel": "Book", "textbook": "Book", "notebook": "Book",
    "pillow": "Pillow", "cushion": "Pillow", "throw pillow": "Pillow",
    "alarm clock": "AlarmClock", "clock": "AlarmClock", "alarm": "AlarmClock",
    "toilet paper": "ToiletPaper", "roll of toilet paper": "ToiletPaper", "toilet roll": "ToiletPaper",
    "tissue roll": "ToiletPaper", "paper roll": "ToiletPaper", "roll": "ToiletPaper", "tp": "ToiletPaper",
    "soap bottle": "SoapBottle", "soap": "SoapBottle", "hand soap": "SoapBottle", "soap dispenser": "SoapBottle",
    "lotion": "SoapBottle", "shampoo": "SoapBottle", "dish soap": "SoapBottle",
    "bar of soap": "SoapBar", "soap bar": "SoapBar",
    "spray bottle": "SprayBottle", "spray": "SprayBottle", "cleaner": "SprayBottle", "spray can": "SprayBottle",
    "newspaper": "Newspaper", "paper": "Newspaper", "news paper": "Newspaper", "magazine": "Newspaper",
    "watch": "Watch", "wristwatch": "Watch", "wrist watch": "Watch",
    "towel": "HandTowel", "hand towel": "HandTowel", "rag": "Cloth", "cloth": "Cloth", "washcloth": "Cloth",
    "wash cloth": "Cloth", "dish towel": "Cloth", "dish rag": "Cloth",
    "pen": "Pen", "pencil": "Pencil",
    "tennis racket": "TennisRacket", "racket": "TennisRacket", "racquet": "TennisRacket",
    "tennis racquet": "TennisRacket",
    "vase": "Vase", "tissue box": "TissueBox", "tissues": "TissueBox", "box of tissues": "TissueBox",
    "kleenex": "TissueBox", "tissue": "TissueBox",
    "basketball": "BasketBall", "basket ball": "BasketBall", "ball": "BasketBall",
    "wine bottle": "WineBottle", "bottle of wine": "WineBottle", "wine": "WineBottle",
    "watering can": "WateringCan", "watering pot": "WateringCan", "plunger": "Plunger",
    "bat": "BaseballBat", "baseball bat": "BaseballBat",
    "pepper shaker": "PepperShaker", "pepper": "PepperShaker", "pepper grinder": "PepperShaker",
    "salt shaker": "SaltShaker", "salt": "SaltShaker", "shaker": "SaltShaker",
    "bottle": ("SoapBottle", "Bottle", "WineBottle"), "glass bottle": "Bottle",
    "sponge": "DishSponge", "dish sponge": "DishSponge", "scrubber": "DishSponge",
    "kettle": "Kettle", "tea kettle": "Kettle", "teapot": "Kettle", "tea pot": "Kettle",
    "knife": "Knife", "butter knife": "ButterKnife", "kitchen knife": "Knife", "bread knife": "Knife",
    "spoon": "Spoon", "ladle": "Ladle", "fork": "Fork", "spatula": "Spatula",
    "potato": "Potato", "potatoes": "Potato", "spud": "Potato", "tater": "Potato",
    "apple": "Apple", "tomato": "Tomato", "tomatoes": "Tomato", "tomatoe": "Tomato", "tomatos": "Tomato",
    "bread": "Bread", "loaf": "Bread", "loaf of bread": "Bread", "bread loaf": "Bread", "toast": "Bread",
    "lettuce": "Lettuce", "head of lettuce": "Lettuce", "cabbage": "Lettuce", "salad": "Lettuce",
    "egg": "Egg", "eggs": "Egg",
    "plate": "Plate", "dish": "Plate", "saucer": "Plate",
    "bowl": "Bowl", "pan": "Pan", "frying pan": "Pan", "skillet": "Pan", "fry pan": "Pan",
    "pot": "Pot", "saucepan": "Pot", "sauce pan": "Pot", "cooking pot": "Pot", "kettle pot": "Pot",
    "box": "Box", "cardboard box": "Box", "statue": "Statue", "figurine": "Statue", "sculpture": "Statue",
    "statuette": "Statue", "candle": "Candle", "teddy bear": "TeddyBear", "plant": "HousePlant",
    "tv": "Television", "television": "Television", "painting": "Painting", "picture": "Painting",
}

# Words that never name an object even though a type name contains them.
STOPWORDS = {"the", "a", "an", "of", "to", "on", "in", "and", "it", "with", "then", "into", "onto", "from"}


def split_camel(name: str) -> str:
    """`CounterTop` -> `counter top`, `CD` -> `cd`."""
    return re.sub(r"(?<=[a-z])(?=[A-Z])", " ", name).lower()


def build_lexicon(type_names: list[str]) -> dict[str, tuple[str, ...]]:
    """phrase -> candidate types, from the type names plus the authored synonyms (which win)."""
    lexicon: dict[str, tuple[str, ...]] = {}
    for name in type_names:
        spaced = split_camel(name)
        for phrase in {spaced, spaced.replace(" ", "")}:
            if phrase not in STOPWORDS:
                lexicon[phrase] = (name,)
    for phrase, types in SYNONYMS.items():
        lexicon[phrase] = types if isinstance(types, tuple) else (types,)
    return lexicon
