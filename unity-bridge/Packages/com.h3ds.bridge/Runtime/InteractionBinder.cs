// Makes the objects AI2-THOR spawned touchable with the Meta XR Interaction SDK at run time and turns
// their events into glove events. Per object: a HandGrabInteractable (on the object's Rigidbody) and an
// InteractableUnityEventWrapper, added while the object is inactive and injected before it wakes, so
// their Awake/Start see the injected references. This is for touch events: to let the person move the
// object too, add a Grabbable and inject it as the interactable's pointable element. The wrapper's events carry no arguments: the hand and
// fingers are read from the interactable's (selecting) interactor views.
using System;
using System.Collections.Generic;
using Oculus.Interaction;
using Oculus.Interaction.HandGrab;
using Oculus.Interaction.Input;
using H3ds.Bridge.Protocol;
using UnityEngine;

namespace H3ds.Bridge
{
    public class InteractionBinder : MonoBehaviour
    {
        /// <summary>kind (hover/unhover/select/unselect), object, hand (left/right), fingers.</summary>
        public event Action<string, SpawnedObject, string, List<string>> Interaction;

        readonly List<InteractableUnityEventWrapper> _wrappers = new List<InteractableUnityEventWrapper>();
        readonly Dictionary<string, string> _lastHand = new Dictionary<string, string>();
        readonly Dictionary<string, List<string>> _lastFingers = new Dictionary<string, List<string>>();

        /// <summary>Adds the interaction components to every spawned object that has a Rigidbody.</summary>
        public int Bind(IEnumerable<SpawnedObject> objects)
        {
            int bound = 0;
            foreach (var spawned in objects)
            {
                var go = spawned.GameObject;
                if (go == null) continue;
                var body = go.GetComponent<Rigidbody>();
                if (body == null) continue;  // fixed parts of the house (walls, counters built in) are not grabbed
                go.SetActive(false);
                var interactable = go.AddComponent<HandGrabInteractable>();
                interactable.InjectRigidbody(body);  // grab types and rules keep their defaults
                var wrapper = go.AddComponent<InteractableUnityEventWrapper>();
                wrapper.InjectAllInteractableUnityEventWrapper(interactable);
                go.SetActive(true);
                var obj = spawned;
                wrapper.WhenHover.AddListener(() => Raise("hover", obj, interactable.InteractorViews));
                wrapper.WhenUnhover.AddListener(() => Raise("unhover", obj, null));
                wrapper.WhenSelect.AddListener(() => Raise("select", obj, interactable.SelectingInteractorViews));
                wrapper.WhenUnselect.AddListener(() => Raise("unselect", obj, null));
                _wrappers.Add(wrapper);
                bound++;
            }
            return bound;
        }

        /// <summary>Removes the wrappers' listeners (before the next house replaces these objects).</summary>
        public void Clear()
        {
            foreach (var w in _wrappers)
            {
                if (w == null) continue;
                Destroy(w);
            }
            _wrappers.Clear();
            _lastHand.Clear();
            _lastFingers.Clear();
        }

        void Raise(string kind, SpawnedObject obj, IEnumerable<IInteractorView> views)
        {
            string hand = null;
            List<string> fingers = null;
            if (views != null)
                foreach (var view in views)
                {
                    var grab = view as HandGrabInteractor;
                    if (grab == null || grab.Hand == null) continue;
                    hand = grab.Hand.Handedness == Handedness.Left ? "left" : "right";
                    fingers = GloveRules.FingerNames((int)grab.GrabbingFingers());
                    if (fingers.Count == 0 && kind == "hover") fingers.Add("palm");
                    break;
                }
            // Unhover / unselect come after the interactor has left: report the hand that was there.
            if (hand == null) _lastHand.TryGetValue(obj.ObjectId, out hand);
            if (fingers == null) _lastFingers.TryGetValue(obj.ObjectId, out fingers);
            hand = hand ?? "right";
            _lastHand[obj.ObjectId] = hand;
            _lastFingers[obj.ObjectId] = fingers ?? new List<string>();
            var handler = Interaction;
            if (handler != null) handler(kind, obj, hand, fingers ?? new List<string>());
        }
    }
}
