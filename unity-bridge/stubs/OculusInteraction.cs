// STUB, not the Meta XR Interaction SDK: the members the bridge uses, named and typed as in
// com.meta.xr.sdk.interaction (Oculus.Interaction, Oculus.Interaction.HandGrab, Oculus.Interaction.Input).
// Agreement with this file proves agreement with this file only, not with the SDK.
using System;
using System.Collections.Generic;
using UnityEngine;
using UnityEngine.Events;

namespace Oculus.Interaction.Input
{
    public enum Handedness { Left = 0, Right = 1 }

    [Flags]
    public enum HandFingerFlags
    {
        None = 0, Thumb = 1 << 0, Index = 1 << 1, Middle = 1 << 2, Ring = 1 << 3, Pinky = 1 << 4,
        All = Thumb | Index | Middle | Ring | Pinky,
    }

    public interface IHand
    {
        Handedness Handedness { get; }
    }
}

namespace Oculus.Interaction
{
    public enum InteractableState { Normal, Hover, Select, Disabled }

    public interface IInteractorView
    {
        int Identifier { get; }
        object Data { get; }
        bool HasInteractable { get; }
        bool HasSelectedInteractable { get; }
    }

    public interface IInteractableView
    {
        object Data { get; }
        InteractableState State { get; }
        int InteractorViewsCount { get; }
        IEnumerable<IInteractorView> InteractorViews { get; }
        int SelectingInteractorViewsCount { get; }
        IEnumerable<IInteractorView> SelectingInteractorViews { get; }
    }

    public class InteractableUnityEventWrapper : MonoBehaviour
    {
        public UnityEvent WhenHover { get { return null; } }
        public UnityEvent WhenUnhover { get { return null; } }
        public UnityEvent WhenSelect { get { return null; } }
        public UnityEvent WhenUnselect { get { return null; } }
        public void InjectAllInteractableUnityEventWrapper(IInteractableView interactableView) { }
        public void InjectInteractableView(IInteractableView interactableView) { }
    }

    public class Grabbable : MonoBehaviour
    {
        public void InjectOptionalRigidbody(Rigidbody rigidbody) { }
    }
}

namespace Oculus.Interaction.Grab
{
    [System.Flags]
    public enum GrabTypeFlags { None = 0, Pinch = 1 << 0, Palm = 1 << 1, All = Pinch | Palm }

    [System.Serializable]
    public struct GrabbingRule { }
}

namespace Oculus.Interaction.HandGrab
{
    using Oculus.Interaction.Grab;
    using Oculus.Interaction.Input;

    public class HandGrabInteractable : MonoBehaviour, IInteractableView
    {
        public object Data { get { return null; } }
        public InteractableState State { get { return InteractableState.Normal; } }
        public int InteractorViewsCount { get { return 0; } }
        public IEnumerable<IInteractorView> InteractorViews { get { yield break; } }
        public int SelectingInteractorViewsCount { get { return 0; } }
        public IEnumerable<IInteractorView> SelectingInteractorViews { get { yield break; } }
        // The InjectAll... overload differs between SDK versions (argument order, GrabbingRule); the bridge
        // calls InjectRigidbody, present in all of them; the grab types and rules keep their field defaults.
        public void InjectAllHandGrabInteractable(GrabTypeFlags supportedGrabTypes, Rigidbody rigidbody,
            GrabbingRule pinchGrabRules, GrabbingRule palmGrabRules) { }
        public void InjectRigidbody(Rigidbody rigidbody) { }
        public void InjectOptionalPointableElement(Grabbable pointableElement) { }
    }

    public class HandGrabInteractor : MonoBehaviour, IInteractorView
    {
        public int Identifier { get { return 0; } }
        public object Data { get { return null; } }
        public bool HasInteractable { get { return false; } }
        public bool HasSelectedInteractable { get { return false; } }
        public IHand Hand { get { return null; } }
        public HandFingerFlags GrabbingFingers() { return HandFingerFlags.None; }
    }
}
